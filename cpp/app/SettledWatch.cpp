#include "app/SettledWatch.h"
#include "scene/SceneLoader.h"
#include "scene/YamlRead.h"
#include <algorithm>
#include <cmath>

namespace cellphase
{
SettledWatch::SettledWatch(scene::SettledStop stop, std::string scene_source)
    : stop_(std::move(stop)), source_(std::move(scene_source))
{
}

void SettledWatch::add(const std::vector<ObservableColumn>& columns)
{
  if (!column_)
  {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < columns.size(); ++i)
    {
      if (columns[i].name == stop_.observable)
        column_ = i;
      names.push_back(columns[i].name);
    }
    if (!column_)
      throw scene::SceneError(source_ + ": numerics.stop_when_settled.observable: found \""
                              + stop_.observable + "\", which is no column of this run's "
                              "observables.csv; its columns are: " + scene::yaml::join(names));
  }
  rows_.emplace_back(columns[0].value, columns[*column_].value); // column 0 is the time
  // Only the window and the last row before it are needed.
  const double start = rows_.back().first - stop_.over;
  while (rows_.size() > 2 && rows_[1].first <= start)
    rows_.pop_front();
}

std::optional<std::string> SettledWatch::settled() const
{
  if (rows_.empty())
    return std::nullopt;
  const auto [now, value] = rows_.back();
  const double start = now - stop_.over;
  // A full window after `after`, and a row at its start or before it (times within 1e-9
  // of a step count as equal).
  const double tolerance = 1e-9 * std::max(1.0, std::abs(now));
  if (start < stop_.after - tolerance || rows_.front().first > start + tolerance)
    return std::nullopt;
  double low = value, high = value;
  for (auto row = rows_.rbegin(); row != rows_.rend() && row->first >= start - tolerance; ++row)
    low = std::min(low, row->second), high = std::max(high, row->second);
  const double bound = std::max(stop_.relative * std::abs(value), stop_.absolute);
  if (!(high - low <= bound)) // NaN never settles
    return std::nullopt;
  return stop_.observable + " varied by " + scene::yaml::fmt(high - low) + " (at most "
         + scene::yaml::fmt(bound) + ") over t = " + scene::yaml::fmt(start) + " ... "
         + scene::yaml::fmt(now) + "; now " + scene::yaml::fmt(value);
}
} // namespace cellphase
