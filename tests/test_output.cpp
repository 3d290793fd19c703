// Where rt writes its image: regular files replaced atomically with their mode, symlinks
// followed, devices, FIFOs and sockets written in place, and every refusal made before
// rendering with a reason. Device nodes are made with mknod in the test's own directory (as
// root only); the real /dev is never written.
#include <stdlib.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>

#include <cstring>

#include "check.h"
#include "common/output_file.h"
#include "process_util.h"

using namespace rt_test;
namespace fs = std::filesystem;

namespace {

const std::string kScene = kSmallScene;
constexpr std::size_t kImageSize = 11 + 8 * 6 * 3;
constexpr const char* kKeep = "previous image, must survive";

// A directory with the scene, readable by every user (so that tests can switch to nobody).
fs::path scene_dir(const std::string& name) {
    const fs::path dir = work_dir(name);
    ::chmod(dir.c_str(), 0755);
    write_file(dir / "scene.in", kScene);
    return dir;
}

mode_t mode_of(const fs::path& path) {
    struct stat st {};
    ::lstat(path.c_str(), &st);
    return st.st_mode;
}

}  // namespace

TEST(a_regular_file_is_replaced_with_its_mode) {
    const fs::path dir = scene_dir("mode");
    for (const mode_t mode : {0600, 0640, 0644, 0755}) {
        write_file(dir / "out.ppm", kKeep);
        ::chmod((dir / "out.ppm").c_str(), mode);
        const RunResult r = run_rt(dir, "scene.in --no-metadata -o out.ppm");
        CHECK_EQ(r.status, 0);
        CHECK_EQ(read_file(dir / "out.ppm").size(), kImageSize);
        CHECK_EQ(mode_of(dir / "out.ppm") & 07777, mode);
    }
    // A new file gets what a shell redirect would: 0666 less the umask.
    CHECK_EQ(run_rt(dir, "scene.in --no-metadata -o new.ppm; umask 027; '" RT_BINARY
                         "' scene.in --no-metadata -o new2.ppm")
                 .status,
             0);
    const mode_t mask = ::umask(0);
    ::umask(mask);
    CHECK_EQ(mode_of(dir / "new.ppm") & 0777, 0666 & ~mask);
    CHECK_EQ(mode_of(dir / "new2.ppm") & 0777, static_cast<mode_t>(0640));
    CHECK(litter(dir).empty());
}

TEST(a_symlink_is_followed_and_stays_a_link) {
    const fs::path dir = scene_dir("symlink");
    fs::create_directory(dir / "images");
    write_file(dir / "images/real.ppm", kKeep);
    fs::create_symlink("images/real.ppm", dir / "link.ppm");
    fs::create_symlink("link.ppm", dir / "link2.ppm");  // a chain of two
    CHECK_EQ(run_rt(dir, "scene.in --no-metadata -o link2.ppm").status, 0);
    CHECK(fs::is_symlink(dir / "link.ppm"));
    CHECK(fs::is_symlink(dir / "link2.ppm"));
    CHECK_EQ(read_file(dir / "images/real.ppm").size(), kImageSize);
    CHECK(litter(dir / "images").empty());
    CHECK(litter(dir).empty());
    // A dangling link: the file is created where it points.
    fs::create_symlink("images/new.ppm", dir / "dangling.ppm");
    CHECK_EQ(run_rt(dir, "scene.in --no-metadata -o dangling.ppm").status, 0);
    CHECK(fs::is_symlink(dir / "dangling.ppm"));
    CHECK_EQ(read_file(dir / "images/new.ppm").size(), kImageSize);
    // A loop is an error, not a hang.
    fs::create_symlink("loop2", dir / "loop1");
    fs::create_symlink("loop1", dir / "loop2");
    const RunResult r = run_rt(dir, "scene.in --no-metadata -o loop1");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "loop1: cannot write the image: ");
}

TEST(a_fifo_is_written_in_place) {
    const fs::path dir = scene_dir("fifo");
    CHECK_EQ(::mkfifo((dir / "pipe").c_str(), 0644), 0);
    CHECK_EQ(run_rt(dir, "scene.in --no-metadata -o file.ppm").status, 0);
    std::string received;
    std::thread reader([&] { received = read_file(dir / "pipe"); });
    const RunResult r = run_rt(dir, "scene.in --no-metadata -o pipe");
    reader.join();
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err, std::string());
    CHECK(received == read_file(dir / "file.ppm"));
    CHECK(S_ISFIFO(mode_of(dir / "pipe")));
    CHECK(litter(dir).empty());
}

TEST(a_socket_is_written_in_place) {
    const fs::path dir = scene_dir("socket");
    const int server = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string path = (dir / "sock").string();
    if (path.size() >= sizeof address.sun_path) return;  // a build path too long for a socket
    std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
    CHECK_EQ(::bind(server, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    CHECK_EQ(::listen(server, 1), 0);
    std::string received;
    std::thread reader([&] {
        const int client = ::accept(server, nullptr, nullptr);
        char buffer[4096];
        for (ssize_t n; (n = ::read(client, buffer, sizeof buffer)) > 0;)
            received.append(buffer, static_cast<std::size_t>(n));
        ::close(client);
    });
    const RunResult r = run_rt(dir, "scene.in --no-metadata -o sock");
    reader.join();
    ::close(server);
    CHECK_EQ(r.status, 0);
    CHECK_EQ(received.size(), kImageSize);
    CHECK(S_ISSOCK(mode_of(dir / "sock")));
}

TEST(device_nodes_are_written_in_place) {
    if (!running_as_root()) return;  // mknod needs root; the real /dev is never used
    const fs::path dir = scene_dir("devices");
    CHECK_EQ(::mknod((dir / "null").c_str(), S_IFCHR | 0666, makedev(1, 3)), 0);
    CHECK_EQ(::mknod((dir / "full").c_str(), S_IFCHR | 0666, makedev(1, 7)), 0);
    ::chmod((dir / "null").c_str(), 0666);  // whatever the umask
    fs::create_symlink("null", dir / "null-link");
    for (const char* name : {"null", "null-link"}) {
        const RunResult r = run_rt(dir, std::string("scene.in --no-metadata -o ") + name);
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err, std::string());
    }
    CHECK(S_ISCHR(mode_of(dir / "null")));
    CHECK(fs::is_symlink(dir / "null-link"));
    // As an ordinary user too: nothing is created beside the device.
    ::chmod(dir.c_str(), 0755);
    CHECK_EQ(run_rt_args(dir, {"scene.in", "-o", "null"}, as_user(kNobody)).status, 0);
    // A full device: the error says so, and nothing is left behind.
    const RunResult r = run_rt(dir, "scene.in --no-metadata -o full");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "full: cannot write the image: No space left on device");
    CHECK(S_ISCHR(mode_of(dir / "full")));
    CHECK(litter(dir).empty());
}

TEST(standard_output_through_its_names) {
    const fs::path dir = scene_dir("stdout_names");
    CHECK_EQ(run_rt(dir, "scene.in --no-metadata -o file.ppm").status, 0);
    const std::string image = read_file(dir / "file.ppm");
    // Through a pipe: written in place.
    CHECK(run_rt(dir, "scene.in --no-metadata -o /dev/stdout | cat").out == image);
    CHECK(run_rt(dir, "scene.in --no-metadata -o /proc/self/fd/1 | cat").out == image);
    // Redirected to a file: that file is the symlink's target, replaced.
    CHECK(run_rt(dir, "scene.in --no-metadata -o /dev/stdout").out == image);
}

TEST(a_terminal_is_refused) {
    const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return;  // no ptys
    const char* name = ::ptsname(master);
    const int slave = name != nullptr ? ::open(name, O_RDWR | O_NOCTTY) : -1;
    CHECK(slave >= 0);
    const fs::path dir = scene_dir("terminal");
    RunResult r = run_rt_args(dir, {"scene.in"}, stdout_to(slave));
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "<stdout>: cannot write the image: standard output is a terminal");
    r = run_rt_args(dir, {"scene.in", "-o", name});
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "it is a terminal");
    // -r prints text, which a terminal takes.
    r = run_rt_args(dir, {"-r", "scene.in"}, stdout_to(slave));
    CHECK_EQ(r.status, 0);
    ::close(slave);
    ::close(master);
}

// A scene typed at a terminal: rt says it is reading it, and one Ctrl-D ends it, as for cat.
TEST(a_scene_typed_at_a_terminal_ends_with_one_ctrl_d) {
    const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return;  // no ptys
    const char* name = ::ptsname(master);
    const int slave = name != nullptr ? ::open(name, O_RDWR | O_NOCTTY) : -1;
    CHECK(slave >= 0);
    const fs::path dir = scene_dir("terminal_input");
    // The line discipline is canonical by default: each line goes on its newline, and a
    // Ctrl-D at the start of a line is the end of the input.
    const std::string typed = kScene + "\x04";
    CHECK_EQ(::write(master, typed.data(), typed.size()), static_cast<ssize_t>(typed.size()));
    SpawnOptions options;
    options.stdin_fd = slave;
    const pid_t pid = spawn_rt(dir, {"-o", "out.ppm"}, options);
    const int status = wait_for(pid, std::chrono::seconds(30));
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    CHECK_CONTAINS(read_file(dir / "rt.err"),
                   "rt: reading the scene from the terminal; end it with Ctrl-D");
    CHECK_EQ(read_file(dir / "out.ppm").substr(0, 3), std::string("P6\n"));
    ::close(slave);
    ::close(master);
}

TEST(the_scene_and_its_textures_are_never_written) {
    const fs::path dir = scene_dir("inputs");
    write_file(dir / "tex.ppm", "P3\n1 1\n255\n1 2 3\n");
    fs::create_symlink("tex.ppm", dir / "tex-link.ppm");
    write_file(dir / "textured.in",
               kScene + "1 .5 0 0 0 108 0 0 0 1 0 0 0 1 0 tex.ppm 100 1 1 1 .5 10 0 0 1\n");
    const std::string scene = read_file(dir / "textured.in");
    const std::string texture = read_file(dir / "tex.ppm");
    for (const char* out : {"textured.in", "./textured.in", "tex.ppm", "tex-link.ppm"}) {
        const RunResult r = run_rt(dir, std::string("textured.in -f ppm -o ") + out);
        CHECK_EQ(r.status, 1);
        CHECK_CONTAINS(r.err, "which this render reads: choose another name");
    }
    CHECK_CONTAINS(run_rt(dir, "textured.in -f ppm -o tex.ppm").err, "it is the texture");
    CHECK_CONTAINS(run_rt(dir, "textured.in -f ppm -o textured.in").err, "it is the scene file");
    const int append = ::open((dir / "textured.in").c_str(), O_WRONLY | O_APPEND);
    CHECK_CONTAINS(run_rt_args(dir, {"textured.in"}, stdout_to(append)).err,
                   "it is the scene file");
    ::close(append);
    CHECK(read_file(dir / "textured.in") == scene);
    CHECK(read_file(dir / "tex.ppm") == texture);
    CHECK(litter(dir).empty());
}

TEST(hard_links_are_refused) {
    const fs::path dir = scene_dir("hard_links");
    write_file(dir / "out.ppm", kKeep);
    fs::create_hard_link(dir / "out.ppm", dir / "backup.ppm");
    const RunResult r = run_rt(dir, "scene.in --no-metadata -o out.ppm");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "out.ppm: cannot write the image: the file has 2 hard links");
    CHECK_CONTAINS(r.err, "remove it first");
    CHECK_EQ(read_file(dir / "out.ppm"), std::string(kKeep));
    CHECK_EQ(fs::hard_link_count(dir / "out.ppm"), 2u);
    CHECK(litter(dir).empty());
}

TEST(long_names_get_a_temporary_name_that_fits) {
    const fs::path dir = scene_dir("long_names");
    const long name_max = ::pathconf(dir.c_str(), _PC_NAME_MAX);
    const std::string name(static_cast<std::size_t>(name_max > 0 ? name_max : 255), 'x');
    write_file(dir / name, kKeep);
    const RunResult r = run_rt(dir, "scene.in --no-metadata -o " + name);
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err, std::string());
    CHECK_EQ(read_file(dir / name).size(), kImageSize);
    CHECK(litter(dir).empty());
}

TEST(refusals_happen_before_rendering_and_say_why) {
    const fs::path dir = scene_dir("refusals");
    RunResult r = run_rt(dir, "scene.in --no-metadata -o no/such/dir/out.ppm");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "no/such/dir/out.ppm: cannot write the image: ");
    fs::create_directory(dir / "adir");
    r = run_rt(dir, "scene.in --no-metadata -o adir");
    CHECK_CONTAINS(r.err, "adir: cannot write the image: it is a directory");
    r = run_rt(dir, "scene.in --no-metadata -o adir/");
    CHECK_CONTAINS(r.err, "it is a directory");
    // A write-protected file is refused for an ordinary user, as a shell redirect refuses it;
    // root may write it, as a redirect may.
    write_file(dir / "locked.ppm", kKeep);
    ::chmod((dir / "locked.ppm").c_str(), 0444);
    if (running_as_root()) {
        ::chmod(dir.c_str(), 0777);
        r = run_rt_args(dir, {"scene.in", "-o", "locked.ppm"}, as_user(kNobody));
        CHECK_EQ(r.status, 1);
        CHECK_CONTAINS(r.err, "the file is write-protected (mode 0444): make it writable");
        CHECK_EQ(read_file(dir / "locked.ppm"), std::string(kKeep));
        // A writable file in a directory the user may not write: the directory is named.
        const fs::path ro = dir / "readonly";
        fs::create_directory(ro);
        write_file(ro / "open.ppm", kKeep);
        ::chmod((ro / "open.ppm").c_str(), 0666);
        ::chmod(ro.c_str(), 0755);
        r = run_rt_args(dir, {"scene.in", "-o", "readonly/open.ppm"}, as_user(kNobody));
        CHECK_EQ(r.status, 1);
        CHECK_CONTAINS(r.err, "the directory 'readonly' is not writable");
        CHECK_EQ(read_file(ro / "open.ppm"), std::string(kKeep));
        // A sticky directory (like /tmp) where the file belongs to someone else.
        const fs::path sticky = dir / "sticky";
        fs::create_directory(sticky);
        ::chmod(sticky.c_str(), 01777);
        write_file(sticky / "theirs.ppm", kKeep);
        ::chmod((sticky / "theirs.ppm").c_str(), 0666);
        r = run_rt_args(dir, {"scene.in", "-o", "sticky/theirs.ppm"}, as_user(kNobody));
        CHECK_EQ(r.status, 1);
        CHECK_CONTAINS(r.err, "has the sticky bit set");
        CHECK_EQ(read_file(sticky / "theirs.ppm"), std::string(kKeep));
        CHECK_EQ(run_rt_args(dir, {"scene.in", "-o", "sticky/mine.ppm"}, as_user(kNobody)).status,
                 0);
        CHECK(litter(sticky).empty());
        // Root replaces the 0444 file and keeps its mode.
        r = run_rt(dir, "scene.in --no-metadata -o locked.ppm");
        CHECK_EQ(r.status, 0);
        CHECK_EQ(mode_of(dir / "locked.ppm") & 0777, static_cast<mode_t>(0444));
    } else {
        r = run_rt(dir, "scene.in --no-metadata -o locked.ppm");
        CHECK_EQ(r.status, 1);
        CHECK_CONTAINS(r.err, "the file is write-protected (mode 0444)");
        CHECK_EQ(read_file(dir / "locked.ppm"), std::string(kKeep));
    }
    CHECK(litter(dir).empty());
}

TEST(output_file_as_a_library) {
    const fs::path dir = work_dir("library");
    {
        rt::OutputFile out((dir / "bytes.bin").string());
        CHECK(!litter(dir).empty());  // claimed before anything is written
        out.write_bytes("hello");
    }
    CHECK_EQ(read_file(dir / "bytes.bin"), std::string("hello"));
    {
        rt::OutputFile abandoned((dir / "bytes.bin").string());  // never written: no change
    }
    CHECK_EQ(read_file(dir / "bytes.bin"), std::string("hello"));
    CHECK(litter(dir).empty());
}

TEST(signals_remove_the_temporary_file_and_end_rt_by_the_signal) {
    const fs::path dir = scene_dir("signals");
    write_file(dir / "slow.in", kSlowScene);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
        write_file(dir / "out.ppm", kKeep);
        const pid_t pid = spawn_rt(dir, {"-j", "1", "-s", "8", "slow.in", "-o", "out.ppm"});
        // The temporary file exists from just before rendering starts.
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
        while (litter(dir).empty() && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        CHECK(!litter(dir).empty());
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        ::kill(pid, sig);
        const int status = wait_for(pid);
        CHECK(WIFSIGNALED(status));
        CHECK_EQ(WIFSIGNALED(status) ? WTERMSIG(status) : 0, sig);
        CHECK_EQ(read_file(dir / "rt.err"), std::string("rt: interrupted\n"));
        CHECK(litter(dir).empty());
        CHECK_EQ(read_file(dir / "out.ppm"), std::string(kKeep));
    }
}
