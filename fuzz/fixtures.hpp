#pragma once
// What the fuzz targets share: a folder holding the record files a fuzzed scene may name.

#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace pounding::fuzz {

/// A folder (created once per process) with `record.txt` (columns, m/s2) and `record.AT2`
/// (PEER, older header), both valid, so fuzzed scenes can get past the record check.
const std::filesystem::path& fixture_folder();

}  // namespace pounding::fuzz

/// The libFuzzer entry point each target defines. Must not throw; crashes are findings.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
