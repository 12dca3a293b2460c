// Replays inputs through the fuzz target's entry point (scene_loader_fuzz.cpp) without libFuzzer,
// so that every compiler runs it: `scene_loader_fuzz_replay FILE_OR_DIR ...` feeds each file
// once. CTest runs it in the default run over the seed scenes and tests/fuzz/findings/, where
// every input the fuzzer ever found at fault is kept: a finding stays a test after its fix.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

int replayFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        std::fprintf(stderr, "scene_loader_fuzz_replay: cannot read %s\n", path.c_str());
        return 1;
    }
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    int failures = 0;
    int replayed = 0;
    for (int i = 1; i < argc; ++i) {
        const fs::path argument(argv[i]);
        if (fs::is_directory(argument)) {
            std::vector<fs::path> files;
            for (const fs::directory_entry& entry : fs::directory_iterator(argument))
                if (entry.is_regular_file() && entry.path().extension() != ".md") files.push_back(entry.path());
            std::sort(files.begin(), files.end());  // a stable order, for a readable log
            for (const fs::path& file : files) failures += replayFile(file), ++replayed;
        } else {
            failures += replayFile(argument), ++replayed;
        }
    }
    std::printf("scene_loader_fuzz_replay: %d inputs replayed\n", replayed);
    return failures == 0 ? 0 : 1;
}
