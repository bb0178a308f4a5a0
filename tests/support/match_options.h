// SPDX-License-Identifier: MIT
// Match options the tests share.
#pragma once

#include "genflow/matching/match.h"

namespace genflow::test {

/// The defaults with one reading (MatchOptions::signatures_reading off): the signatures'
/// reading makes every match twice, and has its own tests
/// (Match.SignaturesReadingKeepsTheReadingThatCommutesBetter and the FAUST_r one).
inline MatchOptions one_reading_options() {
    MatchOptions options;
    options.signatures_reading.enabled = false;
    return options;
}

}  // namespace genflow::test
