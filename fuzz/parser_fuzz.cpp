// SPDX-License-Identifier: MIT
// libFuzzer entry point, compiled once per format (GENFLOW_FUZZ_FORMAT is MeshFormat::Ply, ...):
// any byte string must parse or raise IoError, never crash, hang or allocate without bound.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "genflow/exceptions.h"
#include "genflow/io/read_mesh.h"
#include "genflow/mesh/validate.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        genflow::VertexAttributes attributes;  // the per-vertex data too
        const auto mesh =
            genflow::parse_mesh(std::string_view(reinterpret_cast<const char*>(data), size),
                                GENFLOW_FUZZ_FORMAT, "<fuzz>", nullptr, &attributes);
        (void)genflow::validate(mesh);  // whatever parses must also validate without crashing
    } catch (const genflow::IoError&) {
    }
    return 0;
}
