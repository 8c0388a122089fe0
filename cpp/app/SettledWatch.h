// numerics.stop_when_settled: watches one column of the observables and says when it has
// settled, so that a run towards a stationary state (a moving cell's speed, a tank-treading
// angle) stops there instead of at end_time. The rows are those of observables.csv; a
// restart takes the rows up to its checkpoint back from that file.
#pragma once
#include "io/ObservablesCsv.h"
#include "scene/Scene.h"
#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cellphase
{
class SettledWatch
{
public:
  SettledWatch(scene::SettledStop stop, std::string scene_source);

  /// The rows so far of a restarted run (time, value), from its observables.csv.
  void restore(const std::vector<std::pair<double, double>>& rows)
  {
    rows_.assign(rows.begin(), rows.end());
  }
  /// Adds a row; the first one names the columns, and an observable that is not among
  /// them is a scene error naming the key and the columns there are.
  void add(const std::vector<ObservableColumn>& columns);
  /// After the last row: why the observable counts as settled, or nothing.
  std::optional<std::string> settled() const;

private:
  scene::SettledStop stop_;
  std::string source_;
  std::deque<std::pair<double, double>> rows_; ///< (time, value): the window and one before
  std::optional<std::size_t> column_;
};
} // namespace cellphase
