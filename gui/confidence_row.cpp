#include "gui/confidence_row.hpp"

#include <QHBoxLayout>
#include <QPushButton>

namespace palprig::gui {

ConfidenceRow::ConfidenceRow(QWidget* parent) : QWidget(parent) {
  setObjectName("confidence_row");
  new QHBoxLayout(this);
}

void ConfidenceRow::set_scale(const ConfidenceScale& scale) {
  for (QPushButton* b : buttons_) delete b;
  buttons_.clear();
  labels_.clear();
  for (int level = 1; level <= scale.levels; ++level) {
    const QString label =
        scale.labels.empty() ? QString() : QString::fromStdString(scale.labels[static_cast<std::size_t>(level - 1)]);
    labels_ << label;
    auto* b = new QPushButton(label.isEmpty() ? QString::number(level) : QString("%1  %2").arg(level).arg(label));
    b->setObjectName(QString("confidence_%1").arg(level));
    QFont big = b->font();
    big.setPointSizeF(big.pointSizeF() * 1.5);
    b->setFont(big);
    b->setMinimumHeight(70);
    b->setFocusPolicy(Qt::NoFocus);  // keys go to the screen
    connect(b, &QPushButton::clicked, this, [this, level] { emit rated(level); });
    layout()->addWidget(b);
    buttons_.push_back(b);
  }
}

QString ConfidenceRow::legend() const {
  QStringList parts;
  for (int i = 0; i < labels_.size(); ++i) {
    parts << (labels_[i].isEmpty() ? QString::number(i + 1) : QString("%1 = %2").arg(i + 1).arg(labels_[i]));
  }
  return parts.join(", ");
}

}  // namespace palprig::gui
