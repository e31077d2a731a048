// Over 400 lines: every key of a function scene (layers, inclusions and their shapes, arteries,
// waveforms, respiration) is validated here in the file's order, so each refusal names its field.
#include "formats/function_scene_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/error.hpp"
#include "formats/fe_result_files.hpp"
#include "models/decimal_number.hpp"
#include "io/regular_file.hpp"
#include "models/tissue_scene.hpp"

namespace palprig {

namespace {

constexpr int kMaxShapeNesting = 16;
// Shapes (primitives and the unions etc. joining them) in one inclusion. The tick evaluates an
// inclusion's shape many times a millisecond; a thousand parts is already more than any organ
// model needs, and the bound keeps a hostile file from holding the loader for minutes.
constexpr std::size_t kMaxShapeNodes = 4096;
constexpr std::size_t kMaxBlobTerms = 256;
constexpr double kMaxSize_mm = 1e4;
constexpr double kMaxModulus_kPa = 1e8;  // 100 GPa: stiffer than any bone
// kMaxTickShapeCost (the header): at the 6-7 ns of CPU per sphere-equivalent measured on a
// loaded 2-core EPYC (docs/developing.md "Hardening notes") about 0.2 ms, a fifth of the 1 ms
// period at 1 kHz, so the tick, the backend and a loaded machine still fit. Checked when the
// file is loaded: a scene that cannot be sampled in time is refused before anything moves,
// instead of overrunning the loop (or running a replay for hours).

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Refused with a reason a scene author understands, not just a range.
double positive(const JsonObject& o, const std::string& key, const char* what, double hi = kMaxSize_mm) {
  const auto& v = o.raw(key);
  if (!v.is_number()) o.fail(key, std::string("a positive ") + what + ", got " + json_excerpt(v));
  const double d = v.get<double>();
  if (!std::isfinite(d) || d <= 0)
    o.fail(key, std::string("a positive ") + what + " (sizes and moduli cannot be zero or negative), got " +
                    json_excerpt(v));
  if (d > hi) o.fail(key, std::string("a ") + what + " no larger than " + number_text(hi) + ", got " + json_excerpt(v));
  return d;
}

double positive_or(const JsonObject& o, const std::string& key, double fallback, const char* what,
                   double hi = kMaxSize_mm) {
  return o.has(key) ? positive(o, key, what, hi) : fallback;
}

// A fixed-length array of numbers, e.g. "centre_mm": [x, y, z].
std::vector<double> triple(const JsonObject& o, const std::string& key, std::size_t n, double lo, double hi) {
  const auto& v = o.raw(key);
  if (!v.is_array() || v.size() != n)
    o.fail(key, "an array of " + std::to_string(n) + " numbers, got " + json_excerpt(v));
  return o.numbers(key, lo, hi);
}

std::vector<double> positive_triple(const JsonObject& o, const std::string& key, std::size_t n, const char* what) {
  const auto& v = o.raw(key);
  if (!v.is_array() || v.size() != n)
    o.fail(key, "an array of " + std::to_string(n) + " positive " + what + ", got " + json_excerpt(v));
  for (std::size_t i = 0; i < n; ++i)
    if (!v[i].is_number() || !(v[i].get<double>() > 0) || v[i].get<double>() > kMaxSize_mm)
      throw InputError(o.file(), o.path(key) + "[" + std::to_string(i) + "]",
                       std::string("a positive ") + what + " (no larger than " + number_text(kMaxSize_mm) + "), got " +
                           json_excerpt(v[i]));
  return o.numbers(key, 0, kMaxSize_mm);
}

Point3_mm point3(const JsonObject& o, const std::string& key) {
  const auto v = triple(o, key, 3, -kMaxSize_mm, kMaxSize_mm);
  return {v[0], v[1], v[2]};
}

std::array<double, 3> radii3(const JsonObject& o, const std::string& key) {
  const auto v = positive_triple(o, key, 3, "radii in mm");
  return {v[0], v[1], v[2]};
}

FrepShape::Node parse_shape(const JsonObject& s, FrepShape& shape, int nesting);

std::vector<FrepShape::Node> parse_parts(const JsonObject& s, const std::string& key, FrepShape& shape, int nesting) {
  const auto& list = s.raw(key);
  if (list.is_array() && list.size() > kMaxShapeNodes)  // refused before reading thousands of them
    s.fail(key, "at most " + std::to_string(kMaxShapeNodes) + " shapes in one inclusion, got " +
                    std::to_string(list.size()) + " here");
  std::vector<FrepShape::Node> parts;
  for (const JsonObject& p : s.objects(key)) parts.push_back(parse_shape(p, shape, nesting + 1));
  if (parts.empty()) s.fail(key, "at least one shape");
  return parts;
}

FrepShape::Node parse_shape(const JsonObject& s, FrepShape& shape, int nesting) {
  if (nesting > kMaxShapeNesting) s.fail("type", "shapes nested at most " + std::to_string(kMaxShapeNesting) + " deep");
  if (shape.node_count() >= kMaxShapeNodes)
    s.fail("type", "at most " + std::to_string(kMaxShapeNodes) + " shapes in one inclusion");
  const std::string type = s.choice("type", {"sphere", "ellipsoid", "superellipsoid", "tube", "blobs", "union",
                                             "intersection", "difference", "scaled"});
  FrepShape::Node n = -1;
  if (type == "sphere") {
    n = shape.sphere(point3(s, "centre_mm"), positive(s, "radius_mm", "radius in mm"));
  } else if (type == "ellipsoid") {
    const Point3_mm c = point3(s, "centre_mm");
    n = shape.ellipsoid(c, radii3(s, "radii_mm"), s.number_or("yaw_deg", 0, -360, 360));
  } else if (type == "superellipsoid") {
    const Point3_mm c = point3(s, "centre_mm");
    const auto r = radii3(s, "radii_mm");
    n = shape.superellipsoid(c, r, s.number_or("exponent", 6, 2, 64), s.number_or("yaw_deg", 0, -360, 360));
  } else if (type == "tube") {
    const Point3_mm a = point3(s, "from_mm"), b = point3(s, "to_mm");
    n = shape.tube(a, b, positive(s, "radius_mm", "radius in mm"));
  } else if (type == "blobs") {
    // 001: F = sum k_i exp(-(s_x dx^2 + s_y dy^2 + s_z dz^2)) - c. Each blob gives either the
    // paper's inverse scales s (1/mm^2) or radii r (s = 1/r^2), not both.
    const double c = positive(s, "threshold", "threshold c", 1e6);
    std::vector<Blob> terms;
    // Every blob counts at every point (a sum, not a union): a few hundred is the useful limit.
    if (const auto& list = s.raw("blobs"); list.is_array() && list.size() > kMaxBlobTerms)
      s.fail("blobs",
             "at most " + std::to_string(kMaxBlobTerms) + " blobs in one shape, got " + std::to_string(list.size()));
    for (const JsonObject& b : s.objects("blobs")) {
      Blob t;
      t.centre = point3(b, "centre_mm");
      t.k = positive_or(b, "k", 1.0, "blob weight k", 1e6);
      const bool has_s = b.has("inverse_scale_per_mm2"), has_r = b.has("radii_mm");
      if (has_s == has_r) b.fail("radii_mm", "either \"radii_mm\" or \"inverse_scale_per_mm2\" (exactly one of them)");
      if (has_s) {
        const auto v = positive_triple(b, "inverse_scale_per_mm2", 3, "inverse scales in 1/mm^2");
        t.inverse_scale_per_mm2 = {v[0], v[1], v[2]};
      } else {
        const auto r = radii3(b, "radii_mm");
        t.inverse_scale_per_mm2 = {1 / (r[0] * r[0]), 1 / (r[1] * r[1]), 1 / (r[2] * r[2])};
      }
      b.refuse_unknown();
      terms.push_back(t);
    }
    if (terms.empty()) s.fail("blobs", "at least one blob");
    n = shape.blobs(terms, c);
  } else if (type == "union") {
    n = shape.unite(parse_parts(s, "of", shape, nesting));
  } else if (type == "intersection") {
    n = shape.intersect(parse_parts(s, "of", shape, nesting));
  } else if (type == "difference") {
    const FrepShape::Node from = parse_shape(s.object("from"), shape, nesting + 1);
    const FrepShape::Node minus = parse_shape(s.object("minus"), shape, nesting + 1);
    n = shape.subtract(from, minus);
  } else if (type == "scaled") {
    // Enlarged organs are the normal organ scaled (001): "factor" is one number or one per axis.
    std::array<double, 3> f{};
    const auto& fv = s.raw("factor");
    if (fv.is_number()) {
      const double k = positive(s, "factor", "scale factor", 100);
      f = {k, k, k};
    } else {
      const auto v = positive_triple(s, "factor", 3, "scale factors");
      f = {v[0], v[1], v[2]};
    }
    const Point3_mm about = point3(s, "about_mm");
    n = shape.scaled(parse_shape(s.object("shape"), shape, nesting + 1), about, f);
  }
  s.refuse_unknown();
  return n;
}

InclusionKind parse_kind(const JsonObject& o) {
  const std::string k = o.choice_or("kind", "tumor", {"tumor", "organ", "bone", "ligament", "other"});
  if (k == "organ") return InclusionKind::organ;
  if (k == "bone") return InclusionKind::bone;
  if (k == "ligament") return InclusionKind::ligament;
  if (k == "other") return InclusionKind::other;
  return InclusionKind::tumor;
}

PulseWaveform parse_waveform(const JsonObject& w, const std::filesystem::path& scene_path) {
  const std::string shape = w.choice("shape", {"rectangular", "sawtooth", "table"});
  PulseWaveform out;
  if (shape == "rectangular") {
    const double duty = w.number_or("duty", 0.2, 0.01, 0.99);
    out = PulseWaveform::rectangular(duty);
  } else if (shape == "sawtooth") {
    out = PulseWaveform::sawtooth(w.number_or("rise_fraction", 0.15, 0.01, 0.99));
  } else {
    std::filesystem::path file = w.string("file");
    if (file.is_relative()) file = scene_path.parent_path() / file;
    // Checked before it is opened: opening a FIFO blocks, /dev/zero reads for ever.
    const std::string refusal = waveform_file_refusal(file);
    if (!refusal.empty()) w.fail("file", refusal);
    out = load_waveform_csv(file);
  }
  w.refuse_unknown();
  return out;
}

ArterySpec parse_artery(const JsonObject& a, const std::filesystem::path& scene_path) {
  ArterySpec s;
  s.name = a.string("name");
  const auto& path = a.raw("path_mm");
  if (!path.is_array() || path.size() < 2)
    a.fail("path_mm", "an array of at least 2 points [x, y] along the artery's centreline, got " + json_excerpt(path));
  for (std::size_t i = 0; i < path.size(); ++i) {
    const auto& p = path[i];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number() ||
        !std::isfinite(p[0].get<double>()) || !std::isfinite(p[1].get<double>()))
      throw InputError(a.file(), a.path("path_mm") + "[" + std::to_string(i) + "]",
                       "a point [x_mm, y_mm], got " + json_excerpt(p));
    s.path.push_back({p[0].get<double>(), p[1].get<double>()});
  }
  s.radius_mm = positive(a, "radius_mm", "artery radius in mm", 100);
  s.depth_mm = positive(a, "depth_mm", "depth of the centreline in mm", 500);
  if (s.depth_mm < s.radius_mm)
    a.fail("depth_mm", "a centreline depth of at least the radius (" + number_text(s.radius_mm) +
                           " mm): the artery lies under the skin, got " + number_text(s.depth_mm));
  if (a.has("range_mm")) {
    s.range_mm = positive(a, "range_mm", "source range in mm", 500);
    if (s.range_mm <= s.depth_mm)
      a.fail("range_mm", "a range larger than the depth (" + number_text(s.depth_mm) +
                             " mm), or no finger on the skin ever feels the pulse, got " + number_text(s.range_mm));
  }
  s.amplitude_kPa = a.number("amplitude_kPa", 0, 100);
  s.rate_bpm = a.number("rate_bpm", kMinPulseRateBpm, kMaxPulseRateBpm);
  s.phase_offset = a.number_or("phase_offset", 0, -1, 1);
  if (a.has("waveform")) s.waveform = parse_waveform(a.object("waveform"), scene_path);
  s.own_force_window = a.has("force_window_N");
  if (s.own_force_window) {
    const auto fw = triple(a, "force_window_N", 2, 0, 1000);
    if (!(fw[0] < fw[1]))
      a.fail("force_window_N", "[F_min, F_max] with F_min < F_max, got " + json_excerpt(a.raw("force_window_N")));
    s.force_window.min_N = fw[0];
    s.force_window.max_N = fw[1];
  }
  s.force_window.gain = positive_or(a, "force_gain", 1.0, "force window gain mu", 100);
  if (a.has("activation_margin_mm")) s.activation_margin_mm = a.number("activation_margin_mm", 0, 100);
  s.release_margin_mm = a.number_or("release_margin_mm", 0.57, 0, 100);
  a.refuse_unknown();
  return s;
}

}  // namespace

std::string waveform_file_refusal(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return "";  // opening it says "no such file"
  const std::string problem = regular_file_problem(path, kMaxWaveformFileBytes);
  if (problem.empty()) return "";
  return "a regular file of at most " + std::to_string(kMaxWaveformFileBytes / 1024) +
         " KiB holding a waveform table, got " + path.string() + " (" + problem + ")";
}

PulseWaveform load_waveform_csv(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::string refusal = waveform_file_refusal(path);
  if (!refusal.empty()) throw InputError(file, "file", refusal);
  std::istringstream in(read_regular_file(path, kMaxWaveformFileBytes, "a waveform table"));
  std::vector<double> t, v;
  std::string line;
  int line_no = 0;
  bool seen_header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const auto comma = line.find(',');
    if (comma == std::string::npos)
      throw InputError(file, "line " + std::to_string(line_no),
                       "two comma-separated numbers t_s,value, got \"" + line + "\"");
    const std::string a = line.substr(0, comma), b = line.substr(comma + 1);
    double ta = 0, vb = 0;
    const bool ok = parse_decimal(a, ta) == DecimalCell::number && parse_decimal(b, vb) == DecimalCell::number;
    if (!ok) {
      if (t.empty() && !seen_header) {  // a header line before the first row
        seen_header = true;
        continue;
      }
      throw InputError(file, "line " + std::to_string(line_no), "two numbers t_s,value, got \"" + line + "\"");
    }
    t.push_back(ta);
    v.push_back(vb);
  }
  if (t.empty()) throw InputError(file, "table", "at least 4 rows t_s,value over one beat (the table is empty)");
  try {
    return PulseWaveform::table(t, v);
  } catch (const BadInput& e) {
    throw InputError(file, "table", e.what());
  }
}

void load_function_scene(const JsonObject& root, const std::filesystem::path& path, SceneFile& out) {
  const std::string file = path.string();
  TissueDefinition tissue;

  const JsonObject body = root.object("body");
  const auto centre = triple(body, "centre_mm", 2, -kMaxSize_mm, kMaxSize_mm);
  const auto half = positive_triple(body, "half_size_mm", 2, "half sizes in mm");
  tissue.body = {{centre[0], centre[1]}, half[0], half[1], body.number_or("exponent", 6, 2, 64)};
  body.refuse_unknown();

  const auto layers = root.objects("layers");
  if (layers.empty()) root.fail("layers", "at least one tissue layer (skin first)");
  if (layers.size() > kMaxLayers) root.fail("layers", "at most " + std::to_string(kMaxLayers) + " layers");
  for (const JsonObject& l : layers) {
    TissueLayer layer;
    layer.name = l.string("name");
    layer.thickness_mm = positive(l, "thickness_mm", "thickness in mm");
    layer.stiffness_kPa = positive(l, "stiffness_kPa", "Young's modulus in kPa", kMaxModulus_kPa);
    if (l.has("drag")) {
      // Paper 000's tissue dragging (section 3.2, eq. 3) for a finger pressed into this layer.
      const JsonObject d = l.object("drag");
      layer.drag.f_stick_N = d.number("f_stick_N", 0.01, 100);
      layer.drag.d_lat_max_mm = d.number("d_lat_max_mm", 0, 100);
      layer.drag.relax_s = d.number_or("relax_s", 0.05, 0, 10);
      layer.drag_given = true;
      d.refuse_unknown();
    }
    l.refuse_unknown();
    tissue.layers.push_back(layer);
  }
  if (root.has("support_kPa"))
    tissue.support_kPa = positive(root, "support_kPa", "Young's modulus in kPa", kMaxModulus_kPa);

  const JsonObject felt = root.object("felt_range_kPa");
  tissue.felt.soft_kPa = positive(felt, "soft", "modulus in kPa felt as 0", kMaxModulus_kPa);
  tissue.felt.hard_kPa = positive(felt, "hard", "modulus in kPa felt as 1", kMaxModulus_kPa);
  if (!(tissue.felt.soft_kPa < tissue.felt.hard_kPa))
    felt.fail("hard", "a modulus above soft (" + number_text(tissue.felt.soft_kPa) + " kPa), got " +
                          number_text(tissue.felt.hard_kPa));
  felt.refuse_unknown();

  if (root.has("press")) {
    const JsonObject p = root.object("press");
    tissue.press.finger_radius_mm =
        positive_or(p, "finger_radius_mm", tissue.press.finger_radius_mm, "radius in mm", 100);
    tissue.press.reference_force_N =
        positive_or(p, "reference_force_N", tissue.press.reference_force_N, "force in N", 1000);
    tissue.press.reference_indentation_mm =
        positive_or(p, "reference_indentation_mm", tissue.press.reference_indentation_mm, "indentation in mm", 100);
    p.refuse_unknown();
  }
  if (root.has("respiration")) {
    const JsonObject r = root.object("respiration");
    tissue.respiration.period_s = r.number("period_s", 0.5, 60);
    r.refuse_unknown();
  }

  std::vector<std::pair<std::string, std::size_t>> tumor_names;  // name, index in "inclusions"
  if (root.has("inclusions")) {
    const auto incs = root.objects("inclusions");
    if (incs.size() > kMaxInclusions)
      root.fail("inclusions", "at most " + std::to_string(kMaxInclusions) + " inclusions");
    for (const JsonObject& o : incs) {
      Inclusion inc;
      inc.name = o.string("name");
      inc.kind = parse_kind(o);
      if (inc.kind == InclusionKind::tumor) tumor_names.emplace_back(inc.name, tissue.inclusions.size());
      inc.stiffness_kPa = positive(o, "stiffness_kPa", "Young's modulus in kPa", kMaxModulus_kPa);
      try {
        parse_shape(o.object("shape"), inc.shape, 0);
      } catch (const InputError&) {
        throw;                       // the loader's own refusal names its field already
      } catch (const BadInput& e) {  // the builders' own checks, should the loader's miss one
        o.fail("shape", e.what());
      }
      if (o.has("breathing_excursion_mm")) inc.breathing_excursion_mm = point3(o, "breathing_excursion_mm");
      o.refuse_unknown();
      tissue.inclusions.push_back(std::move(inc));
    }
  }

  std::vector<ArterySpec> arteries;
  if (root.has("arteries")) {
    const auto list = root.objects("arteries");
    if (list.size() > kMaxArteries) root.fail("arteries", "at most " + std::to_string(kMaxArteries) + " arteries");
    for (const JsonObject& a : list) arteries.push_back(parse_artery(a, path));
  }

  if (root.has("generator")) {  // provenance of a generated case: checked, kept in the file
    const JsonObject g = root.object("generator");
    (void)g.integer("seed", 0, INT64_MAX);
    (void)g.choice("difficulty", {"easy", "medium", "hard"});
    g.refuse_unknown();
  }
  // Render from the finite-element table (`palprig fe table`) instead of the stiffness rule:
  // the table file's path, relative to this scene file.
  std::shared_ptr<const FeStressTable> fe_table;
  if (root.has("fe_stress_table")) {
    const std::string name = root.string("fe_stress_table");
    if (name.empty()) root.fail("fe_stress_table", "the path of a table written by `palprig fe table`");
    std::filesystem::path table_path(name);
    if (table_path.is_relative()) table_path = path.parent_path() / table_path;
    fe_table = load_fe_table_file(table_path).table;
  }
  root.refuse_unknown();

  std::unique_ptr<FunctionScene> scene;
  try {
    scene = std::make_unique<FunctionScene>(std::move(tissue), std::move(arteries));
  } catch (const BadInput& e) {
    throw InputError(file, "scene", e.what());
  }
  const double tick_cost = double(kFingerCount) * scene->field().worst_case_sample_cost();
  if (tick_cost > kMaxTickShapeCost)
    throw InputError(file, "inclusions",
                     "shapes three fingers can sample within a fifth of a 1 kHz tick: at most " +
                         std::to_string(std::llround(kMaxTickShapeCost)) + " shape evaluations per tick, got " +
                         std::to_string(std::llround(tick_cost)) +
                         " where the most inclusion boxes overlap (use fewer parts or blobs where they overlap, unions "
                         "rather than intersections of many parts)");
  // A tumor is ground truth for scoring marks on the body: its centre lies on the body's
  // footprint (centre_mm +- half_size_mm), not metres away where no finger can reach it.
  const double x0 = centre[0] - half[0], x1 = centre[0] + half[0], y0 = centre[1] - half[1], y1 = centre[1] + half[1];
  for (const InclusionOutline& o : scene->outlines(InclusionKind::tumor)) {
    if (!(o.x_mm >= x0 && o.x_mm <= x1 && o.y_mm >= y0 && o.y_mm <= y1)) {
      std::size_t index = 0;
      while (index < tumor_names.size() && tumor_names[index].first != o.name) ++index;
      const std::string where =
          "inclusions[" + std::to_string(index < tumor_names.size() ? tumor_names[index].second : 0) + "].shape";
      throw InputError(file, where,
                       "a tumor centred on the body (x in " + number_text(x0) + ".." + number_text(x1) + " mm, y in " +
                           number_text(y0) + ".." + number_text(y1) + " mm), got '" + o.name + "' at (" +
                           number_text(o.x_mm) + ", " + number_text(o.y_mm) + ") mm");
    }
    out.tumors.push_back({o.name, o.x_mm, o.y_mm, o.radius_mm});
  }
  scene->use_fe_table(std::move(fe_table));
  out.scene = std::move(scene);
}

}  // namespace palprig
