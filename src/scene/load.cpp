// Loading a whole scene: from a stream, a file or standard input (read through a descriptor,
// so that a read error is reported as one), its hierarchy built after.
#include <fcntl.h>
#include <sys/stat.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <istream>

#include "common/fd_stream.h"
#include "rt/error.h"
#include "rt/reader.h"

namespace rt {

Scene read_scene(std::istream& in, const std::string& name, const std::filesystem::path& base_dir,
                 int threads, StageTimes* times, std::vector<SceneInput>* inputs) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    SceneReader reader(in, name, base_dir, threads);
    Scene scene = reader.read_scene();
    if (inputs != nullptr) *inputs = reader.input_files();
    const auto read = Clock::now();
    scene.build_index(threads);
    if (times != nullptr) {
        times->read = std::chrono::duration<double>(read - start).count();
        times->build = std::chrono::duration<double>(Clock::now() - read).count();
    }
    return scene;
}

Scene read_scene_file(const std::string& path, int threads, StageTimes* times,
                      std::vector<SceneInput>* inputs, Sha256* digest) {
    // Read through a descriptor, so that a read error is reported as one, with its reason,
    // rather than taken for the end of the scene.
    if (path == "-") {
        struct stat st {};
        if (::fstat(0, &st) != 0)
            throw Error(std::string("<stdin>: cannot read the scene from standard input: ") +
                        std::strerror(errno));
        FdBuf buffer(0, "<stdin>: cannot read the scene", false);
        buffer.digest_into(digest);
        std::istream in(&buffer);
        return read_scene(in, "<stdin>", std::filesystem::current_path(), threads, times, inputs);
    }
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error(path + ": is a directory, not a scene file");
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw Error(path + ": cannot open scene file: " + std::strerror(errno));
    FdBuf buffer(fd, path + ": cannot read the scene", true);
    buffer.digest_into(digest);
    std::istream in(&buffer);
    return read_scene(in, path, std::filesystem::path(path).parent_path(), threads, times,
                      inputs);
}

}  // namespace rt
