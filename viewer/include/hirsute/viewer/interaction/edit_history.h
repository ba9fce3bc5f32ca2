#pragma once
// The undo history of one editor of the viewer's workbench (docs/viewer.md, "Editors"): every
// editor (colour maps and materials, function curves, contours, surfaces, control panels) keeps
// the states of the document it edits, so that undo and redo step through the session's edits
// and a save writes the state shown. A drag is one edit: the editor records the state before it
// begins and replaces the present state while the mouse moves.

#include <cstddef>
#include <utility>
#include <vector>

namespace hirsute {

template <typename Document>
class EditHistory {
 public:
  // The most states kept: the oldest is forgotten past it, so that a long session's history has
  // a bounded size.
  static constexpr std::size_t kMaxStates = 256;

  explicit EditHistory(Document initial) { states_.push_back(std::move(initial)); }

  const Document& current() const { return states_[position_]; }

  // A new edit: the states that redo would have reached are dropped.
  void record(Document next) {
    if (savedPosition_ > position_) savedDropped_ = true;
    states_.resize(position_ + 1);
    states_.push_back(std::move(next));
    if (states_.size() > kMaxStates) {
      states_.erase(states_.begin());
      if (savedPosition_ == 0) savedDropped_ = true;
      else --savedPosition_;
    }
    position_ = states_.size() - 1;
  }

  // Changes the present state without a new step (the moves of one drag).
  void replaceCurrent(Document next) {
    states_[position_] = std::move(next);
    if (savedPosition_ == position_) savedDropped_ = true;
  }

  bool canUndo() const { return position_ > 0; }
  bool canRedo() const { return position_ + 1 < states_.size(); }
  bool undo() {
    if (!canUndo()) return false;
    --position_;
    return true;
  }
  bool redo() {
    if (!canRedo()) return false;
    ++position_;
    return true;
  }

  // Whether the state shown differs from the one last saved (or read).
  bool modified() const { return position_ != savedPosition_ || savedDropped_; }
  void markSaved() {
    savedPosition_ = position_;
    savedDropped_ = false;
  }

 private:
  std::vector<Document> states_;
  std::size_t position_ = 0;
  std::size_t savedPosition_ = 0;
  bool savedDropped_ = false;
};

}  // namespace hirsute
