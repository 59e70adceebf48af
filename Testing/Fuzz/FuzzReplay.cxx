// SPDX-License-Identifier: BSD-3-Clause
// A main() for a libFuzzer target without libFuzzer: runs LLVMFuzzerTestOneInput once on every
// file named on the command line (folders: every file in them, in name order). Built with the
// normal compiler in every build, it replays the checked-in corpus and its regression inputs
// through the target's invariants on every change (ctest *Corpus); any violation aborts.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int* argc, char*** argv);

int main(int argc, char* argv[])
{
  namespace fs = std::filesystem;
  if (LLVMFuzzerInitialize)
  {
    LLVMFuzzerInitialize(&argc, &argv);
  }
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i)
  {
    if (fs::is_directory(argv[i]))
    {
      for (const auto& entry : fs::directory_iterator(argv[i]))
      {
        files.push_back(entry.path());
      }
    }
    else
    {
      files.emplace_back(argv[i]);
    }
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files)
  {
    std::ifstream in(file, std::ios::binary);
    if (!in)
    {
      std::fprintf(stderr, "cannot read %s\n", file.c_str());
      return 1;
    }
    const std::vector<char> bytes(
      (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("replayed %zu inputs\n", files.size());
  return files.empty() ? 1 : 0;
}
