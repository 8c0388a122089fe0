// Test-only fault injection, driven by environment variables so that no scene key exists
// for it: CELLPHASE_TEST_NAN_AT_STEP=N puts a NaN into one value of a field right after
// step N (the field labelled CELLPHASE_TEST_NAN_FIELD, default phi), so that the tests can
// check the stop on a non-finite field (tests/python/test_failure_paths.py).
// CELLPHASE_TEST_THROW_AT_STEP=N throws an internal error on rank
// CELLPHASE_TEST_THROW_RANK (default 0) alone right after step N, as a bug on one rank would.
#pragma once
#include "core/FieldRegistry.h"

namespace cellphase::test_hooks
{
/// Apply CELLPHASE_TEST_NAN_AT_STEP after `step`; no effect when it is not set.
void inject_nan_after_step(FieldRegistry& fields, int step);

/// Apply CELLPHASE_TEST_THROW_AT_STEP after `step` (rank `rank` of the run); no effect when
/// it is not set.
void throw_on_one_rank_after_step(int step, int rank);
} // namespace cellphase::test_hooks
