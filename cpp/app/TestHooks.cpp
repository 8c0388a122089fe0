#include "app/TestHooks.h"
#include <cmath>
#include <cstdlib>
#include <limits>
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
} // namespace cellphase::test_hooks
