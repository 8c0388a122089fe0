// Test-only fault injection, driven by environment variables so that no scene key exists
// for it: CELLPHASE_TEST_NAN_AT_STEP=N puts a NaN into one value of a field right after
// step N (the field labelled CELLPHASE_TEST_NAN_FIELD, default phi), so that the tests can
// check the stop on a non-finite field (tests/python/test_failure_paths.py).
#pragma once
#include "core/FieldRegistry.h"

namespace cellphase::test_hooks
{
/// Apply CELLPHASE_TEST_NAN_AT_STEP after `step`; no effect when it is not set.
void inject_nan_after_step(FieldRegistry& fields, int step);
} // namespace cellphase::test_hooks
