#pragma once
// ConfidenceRow: the participant screen's rating step, shown after the finger answer when the
// protocol asks for a confidence rating: one button per level (1..levels, with the protocol's
// labels) and keys 1..levels. The screen hands the finger answer and the rating over together.
#include <QWidget>
#include <vector>

#include "study/protocol.hpp"

class QPushButton;

namespace palprig::gui {

class ConfidenceRow final : public QWidget {
  Q_OBJECT
 public:
  explicit ConfidenceRow(QWidget* parent = nullptr);
  // One button per level of `scale` (none when it is not asked).
  void set_scale(const ConfidenceScale& scale);
  int levels() const noexcept { return static_cast<int>(buttons_.size()); }
  // "1 = guess ... 4 = sure" for the prompt.
  QString legend() const;

 signals:
  void rated(int rating);  // 1..levels

 private:
  std::vector<QPushButton*> buttons_;
  QStringList labels_;
};

}  // namespace palprig::gui
