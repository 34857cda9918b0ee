// A main() for the fuzz targets without libFuzzer: runs LLVMFuzzerTestOneInput on every file
// named (directories are walked, in sorted order), so GCC builds the targets and CTest replays
// their corpora and regression inputs. A violation aborts, which fails the test.
//
//   TARGET FILE_OR_DIR...                       replay each input
//   TARGET --random N [--seed S] FILE_OR_DIR... N inputs, each a named input with 1 to 8 random
//                                               bytes replaced, inserted or erased (no coverage
//                                               guidance: long false-alarm runs with any compiler)
#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

bool read_count(const char* text, unsigned long long& out) {
  char* end = nullptr;
  errno = 0;
  out = std::strtoull(text, &end, 10);
  return errno == 0 && end != text && *end == '\0' && text[0] != '-';
}

std::vector<std::uint8_t> mutated(std::vector<std::uint8_t> bytes, std::mt19937_64& random) {
  const int edits = 1 + static_cast<int>(random() % 8);
  for (int e = 0; e < edits; ++e) {
    const std::uint8_t value = static_cast<std::uint8_t>(random());
    const std::size_t at = bytes.empty() ? 0 : random() % bytes.size();
    switch (random() % 4) {
      case 0: bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at), value); break;
      case 1:
        if (!bytes.empty()) bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(at));
        break;
      default:
        if (bytes.empty())
          bytes.push_back(value);
        else
          bytes[at] = value;
    }
  }
  return bytes;
}

/// The exit status after the summary line: 2 when standard output could not take it.
int written(int status) {
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::fprintf(stderr, "cannot write to standard output\n");
    return 2;
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  unsigned long long random_count = 0, seed = 1;
  bool random_mode = false;
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--random" || arg == "--seed") {
      unsigned long long value = 0;
      if (i + 1 >= argc || !read_count(argv[i + 1], value)) {
        std::fprintf(stderr, "%s takes a non-negative integer\n", arg.c_str());
        return 2;
      }
      ++i;
      if (arg == "--random") {
        random_mode = true;
        random_count = value;
      } else {
        seed = value;
      }
      continue;
    }
    const std::filesystem::path path(arg);
    if (std::filesystem::is_directory(path)) {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(path)) {
        if (entry.is_regular_file() && entry.path().extension() != ".md")
          files.push_back(entry.path());
      }
    } else if (std::filesystem::exists(path)) {
      files.push_back(path);
    } else {
      std::fprintf(stderr, "no such input: %s\n", argv[i]);
      return 2;
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<std::vector<std::uint8_t>> inputs;
  for (const auto& file : files) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "cannot read input: %s\n", file.string().c_str());
      return 2;
    }
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                    std::istreambuf_iterator<char>());
    if (random_mode) {
      inputs.push_back(std::move(bytes));
      continue;
    }
    std::fprintf(stderr, "replaying %s\n", file.string().c_str());
    LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
  }
  if (!random_mode) {
    std::printf("replayed %zu inputs\n", files.size());
    return written(files.empty() ? 1 : 0);
  }
  std::mt19937_64 random(seed);
  for (unsigned long long n = 0; n < random_count; ++n) {
    const std::vector<std::uint8_t> input = mutated(
        inputs.empty() ? std::vector<std::uint8_t>{} : inputs[random() % inputs.size()], random);
    LLVMFuzzerTestOneInput(input.data(), input.size());
    if ((n + 1) % 100000 == 0) std::fprintf(stderr, "%llu random inputs run\n", n + 1);
  }
  std::printf("ran %llu random inputs (seed %llu, mutated from %zu named)\n", random_count, seed,
              inputs.size());
  return written(0);
}
