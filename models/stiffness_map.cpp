#include "models/stiffness_map.hpp"

#include <algorithm>
#include <cmath>
#include <istream>
#include <ostream>
#include <sstream>

#include "core/error.hpp"
#include "models/decimal_number.hpp"
#include "core/input_error.hpp"

namespace palprig {

StiffnessMap::StiffnessMap(std::size_t cols, std::size_t rows, double width_mm, double height_mm, MapValues values,
                           OutsidePolicy outside)
    : cols_(cols),
      rows_(rows),
      width_mm_(width_mm),
      height_mm_(height_mm),
      values_(std::move(values)),
      outside_(outside) {
  if (cols < 2 || rows < 2) throw BadInput("StiffnessMap: need at least 2x2 vertices");
  if (!(width_mm > 0) || !(height_mm > 0) || !std::isfinite(width_mm) || !std::isfinite(height_mm))
    throw BadInput("StiffnessMap: width_mm and height_mm must be positive");
  if (values_.size() != cols * rows) throw BadInput("StiffnessMap: values != cols*rows");
  for (float v : values_)
    if (!std::isfinite(v) || v < 0.f || v > 1.f)
      throw BadInput("StiffnessMap: stiffness values must be finite and in 0..1");
  if (!(outside.background_stiffness >= 0 && outside.background_stiffness <= 1))
    throw BadInput("StiffnessMap: background stiffness must be in 0..1");
}

bool StiffnessMap::to_grid(double x_mm, double y_mm, double& gx, double& gy) const noexcept {
  // Non-finite positions never reach here in the tick (safety rejects them); treat as outside.
  const bool inside = x_mm >= 0 && x_mm <= width_mm_ && y_mm >= 0 && y_mm <= height_mm_;
  if (!inside && outside_.kind == OutsidePolicy::Kind::background) return false;
  const double cx = std::clamp(std::isfinite(x_mm) ? x_mm : 0.0, 0.0, width_mm_);
  const double cy = std::clamp(std::isfinite(y_mm) ? y_mm : 0.0, 0.0, height_mm_);
  gx = cx / width_mm_ * double(cols_ - 1);
  gy = cy / height_mm_ * double(rows_ - 1);
  return true;
}

namespace {

// The vertex nearest a grid coordinate g >= 0 (to_grid clamps it): std::lround's result
// (half away from zero) without its library call, which the tick makes for every sample. The
// one input where they differ is g = 0.5 - 2^-54, which g + 0.5 rounds up to vertex 1: a point
// 1e-16 of a cell from half-way, which no pen resolves.
std::size_t nearest_vertex(double g) noexcept {
  return static_cast<std::size_t>(g + 0.5);  // NOLINT(bugprone-incorrect-roundings): g >= 0; the one case above
}

}  // namespace

double StiffnessMap::sample_nearest(double x_mm, double y_mm) const noexcept {
  double gx, gy;
  if (!to_grid(x_mm, y_mm, gx, gy)) return outside_.background_stiffness;
  const std::size_t c = nearest_vertex(gx), r = nearest_vertex(gy);
  return at(std::min(c, cols_ - 1), std::min(r, rows_ - 1));
}

void StiffnessMap::prefetch(double x_mm, double y_mm, MapSampling how) const noexcept {
  double gx, gy;
  if (values_.empty() || !to_grid(x_mm, y_mm, gx, gy)) return;
  std::size_t c, r;
  if (how == MapSampling::nearest) {
    c = std::min(nearest_vertex(gx), cols_ - 1);
    r = std::min(nearest_vertex(gy), rows_ - 1);
  } else {
    c = std::min(static_cast<std::size_t>(gx), cols_ - 2);
    r = std::min(static_cast<std::size_t>(gy), rows_ - 2);
    __builtin_prefetch(&values_[(r + 1) * cols_ + c]);
  }
  __builtin_prefetch(&values_[r * cols_ + c]);
}

double StiffnessMap::sample_bilinear(double x_mm, double y_mm) const noexcept {
  double gx, gy;
  if (!to_grid(x_mm, y_mm, gx, gy)) return outside_.background_stiffness;
  const std::size_t c0 = std::min(static_cast<std::size_t>(gx), cols_ - 2);
  const std::size_t r0 = std::min(static_cast<std::size_t>(gy), rows_ - 2);
  const double fx = gx - double(c0), fy = gy - double(r0);
  const double v00 = at(c0, r0), v10 = at(c0 + 1, r0), v01 = at(c0, r0 + 1), v11 = at(c0 + 1, r0 + 1);
  return (v00 * (1 - fx) + v10 * fx) * (1 - fy) + (v01 * (1 - fx) + v11 * fx) * fy;
}

namespace {

void check_size(const std::string& source, double width_mm, double height_mm) {
  if (!(width_mm > 0) || !std::isfinite(width_mm))
    throw InputError(source, "width_mm", "a positive finite width in mm");
  if (!(height_mm > 0) || !std::isfinite(height_mm))
    throw InputError(source, "height_mm", "a positive finite height in mm");
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

}  // namespace

StiffnessMap parse_stiffness_csv(std::istream& in, const std::string& source, double width_mm, double height_mm,
                                 double value_scale) {
  check_size(source, width_mm, height_mm);
  if (value_scale < 0 || !std::isfinite(value_scale))
    throw InputError(source, "value_scale", "a positive scale (or 0 for values already in 0..1)");
  MapValues values;
  std::size_t cols = 0, rows = 0, line_no = 0;
  std::string line;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    std::size_t n = 0;
    std::stringstream ss(t);
    std::string cell;
    while (std::getline(ss, cell, ',')) {
      ++n;
      const std::string c = trim(cell);
      const std::string where = "line " + std::to_string(line_no) + ", column " + std::to_string(n);
      double v = 0;
      const DecimalCell kind = parse_decimal(c, v);
      if (kind == DecimalCell::not_a_number) throw InputError(source, where, "a number, got '" + c + "'");
      if (kind == DecimalCell::not_finite) throw InputError(source, where, "a finite stiffness, got '" + c + "'");
      if (value_scale > 0) v /= value_scale;
      if (v < 0 || v > 1)
        throw InputError(source, where,
                         value_scale > 0 ? "a value in 0.." + std::to_string(value_scale) + ", got '" + c + "'"
                                         : "a stiffness in 0..1 (or give a value scale), got '" + c + "'");
      if (values.size() >= static_cast<std::size_t>(kMaxMapVertices) || n > static_cast<std::size_t>(kMaxMapSide))
        throw InputError(source, where,
                         "a map of at most " + std::to_string(kMaxMapVertices) + " values (4096x4096) and " +
                             std::to_string(kMaxMapSide) + " a side");
      values.push_back(static_cast<float>(v));
    }
    if (!t.empty() && t.back() == ',')
      throw InputError(source, "line " + std::to_string(line_no), "no trailing comma (empty last value)");
    if (rows == 0)
      cols = n;
    else if (n != cols)
      throw InputError(source, "line " + std::to_string(line_no),
                       std::to_string(cols) + " values like the first row, got " + std::to_string(n));
    ++rows;
  }
  if (rows < 2 || cols < 2)
    throw InputError(source, "line " + std::to_string(line_no),
                     "a grid of at least 2x2 values, got " + std::to_string(cols) + "x" + std::to_string(rows));
  return StiffnessMap(cols, rows, width_mm, height_mm, std::move(values));
}

namespace {

// Reads the next PGM header token, skipping whitespace and '#' comments.
std::string pgm_token(std::istream& in) {
  std::string tok;
  int ch;
  while ((ch = in.get()) != EOF) {
    if (ch == '#') {
      while ((ch = in.get()) != EOF && ch != '\n') {}
      continue;
    }
    if (std::isspace(ch)) {
      if (!tok.empty()) break;
      continue;
    }
    tok.push_back(static_cast<char>(ch));
  }
  return tok;
}

// The next token as an integer in lo..hi; `where` names the header field or pixel.
long pgm_int(std::istream& in, const std::string& source, const std::string& where, long lo, long hi) {
  const std::string tok = pgm_token(in);
  long v = -1;
  std::size_t used = 0;
  try {
    v = std::stol(tok, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (tok.empty() || used != tok.size() || v < lo || v > hi)
    throw InputError(source, where,
                     "an integer in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got '" + tok + "'");
  return v;
}

// Bytes from the read position to the end of a seekable stream (a file, a string).
std::size_t bytes_left(std::istream& in) {
  const auto here = in.tellg();
  if (here < 0) return 0;
  in.seekg(0, std::ios::end);
  const auto end = in.tellg();
  in.seekg(here);
  return end > here ? static_cast<std::size_t>(end - here) : 0;
}

}  // namespace

StiffnessMap parse_stiffness_pgm(std::istream& in, const std::string& source, double width_mm, double height_mm) {
  check_size(source, width_mm, height_mm);
  const std::string magic = pgm_token(in);
  if (magic != "P5" && magic != "P2")
    throw InputError(source, "header magic", "'P5' (binary) or 'P2' (ASCII) PGM, got '" + magic + "'");
  const long cols = pgm_int(in, source, "header width", 2, kMaxMapSide);
  const long rows = pgm_int(in, source, "header height", 2, kMaxMapSide);
  if (cols * rows > kMaxMapVertices)
    throw InputError(source, "header width x height",
                     "at most " + std::to_string(kMaxMapVertices) + " pixels (a map of 4096x4096), got " +
                         std::to_string(cols) + "x" + std::to_string(rows));
  const long maxval = pgm_int(in, source, "header maxval", 1, 65535);
  const std::size_t pixels = static_cast<std::size_t>(cols * rows);
  // What the header promises must be in the file before anything of that size is allocated:
  // a 21-byte file must not be able to ask for gigabytes.
  const int bytes = maxval > 255 ? 2 : 1;
  const std::size_t need = magic == "P5" ? pixels * bytes : 2 * pixels - 1;  // ASCII: digit + space each
  if (const std::size_t left = bytes_left(in); left < need)
    throw InputError(source, "pixel data",
                     std::to_string(need) + (magic == "P5" ? "" : " or more") + " bytes for " + std::to_string(cols) +
                         "x" + std::to_string(rows) + " pixels, the file has " + std::to_string(left));
  MapValues values(pixels);
  if (magic == "P5") {
    std::vector<unsigned char> raw(values.size() * bytes);
    in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(raw.size()));
    if (static_cast<std::size_t>(in.gcount()) != raw.size())
      throw InputError(source, "pixel data",
                       std::to_string(raw.size()) + " bytes for " + std::to_string(cols) + "x" + std::to_string(rows) +
                           " pixels, got " + std::to_string(in.gcount()));
    for (std::size_t i = 0; i < values.size(); ++i) {
      const long v = bytes == 2 ? (long(raw[2 * i]) << 8) | raw[2 * i + 1] : long(raw[i]);
      if (v > maxval)
        throw InputError(source, "pixel " + std::to_string(i), "a value <= maxval " + std::to_string(maxval));
      values[i] = static_cast<float>(double(v) / double(maxval));
    }
  } else {
    for (std::size_t i = 0; i < values.size(); ++i) {
      const long v = pgm_int(in, source, "pixel " + std::to_string(i), 0, maxval);
      values[i] = static_cast<float>(double(v) / double(maxval));
    }
  }
  return StiffnessMap(static_cast<std::size_t>(cols), static_cast<std::size_t>(rows), width_mm, height_mm,
                      std::move(values));
}

void write_stiffness_csv(std::ostream& out, const StiffnessMap& map) {
  out.precision(6);
  for (std::size_t r = 0; r < map.rows(); ++r) {
    for (std::size_t c = 0; c < map.cols(); ++c) out << (c ? "," : "") << map.at(c, r);
    out << '\n';
  }
}

void write_stiffness_pgm16(std::ostream& out, const StiffnessMap& map) {
  out << "P5\n" << map.cols() << ' ' << map.rows() << "\n65535\n";
  for (float v : map.values()) {
    const auto q = static_cast<unsigned>(std::lround(std::clamp(double(v), 0.0, 1.0) * 65535.0));
    out.put(static_cast<char>(q >> 8));
    out.put(static_cast<char>(q & 0xff));
  }
}

}  // namespace palprig
