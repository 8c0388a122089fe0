#include "app/TestHooks.h"
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace cellphase::test_hooks
{
void inject_nan_after_step(FieldRegistry& fields, int step)
{
  const char* at = std::getenv("CELLPHASE_TEST_NAN_AT_STEP");
  if (!at || std::atoi(at) != step)
    return;
  const char* label = std::getenv("CELLPHASE_TEST_NAN_FIELD");
  const std::string name = fields.by_label(label ? label : "phi");
  auto f = name.empty() ? nullptr : fields.find(name);
  if (!f)
    return;
  auto values = f->x()->mutable_array();
  if (!values.empty())
    values[values.size() / 2] = std::numeric_limits<double>::quiet_NaN(); // on every rank
}

void throw_on_one_rank_after_step(int step, int rank)
{
  const char* at = std::getenv("CELLPHASE_TEST_THROW_AT_STEP");
  if (!at || std::atoi(at) != step)
    return;
  const char* on = std::getenv("CELLPHASE_TEST_THROW_RANK");
  if (rank == (on ? std::atoi(on) : 0))
    throw std::logic_error("test: an internal error on this rank alone after step "
                           + std::to_string(step));
}
} // namespace cellphase::test_hooks
