// SPDX-License-Identifier: MIT
// The per-format parsers behind read_mesh()/parse_mesh(). Each takes the whole file in memory.
#pragma once

#include <string_view>

#include "io/parse_context.h"

namespace genflow::detail {

TriangleMesh parse_obj(std::string_view bytes, const ParseContext& context);
TriangleMesh parse_ply(std::string_view bytes, const ParseContext& context);
TriangleMesh parse_off(std::string_view bytes, const ParseContext& context);
TriangleMesh parse_stl(std::string_view bytes, const ParseContext& context);

}  // namespace genflow::detail
