// Replays fuzz inputs without libFuzzer (a g++ build, in `make test`): every file given, or every
// file in a directory given, goes once through LLVMFuzzerTestOneInput. A crash or an escaping
// exception fails the test; the input that did it is printed first.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

#include "fuzz_input.hpp"

namespace {
int replay(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
  std::cerr << "replay " << file.string() << " (" << bytes.size() << " bytes)\n";
  return LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}
}  // namespace

int main(int argc, char** argv) {
  std::size_t inputs = 0;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path p(argv[i]);
    if (std::filesystem::is_directory(p)) {
      for (const auto& e : std::filesystem::directory_iterator(p)) {
        if (e.is_regular_file()) inputs += replay(e.path()) == 0 ? 1 : 0;
      }
    } else {
      inputs += replay(p) == 0 ? 1 : 0;
    }
  }
  if (inputs == 0) {
    std::cerr << "no fuzz inputs found in the arguments; give corpus directories or files\n";
    return 1;
  }
  std::cout << inputs << " inputs replayed\n";
  return 0;
}
