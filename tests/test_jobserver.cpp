// GNU make integration: MAKEFLAGS parsing, the jobserver client on pipes and FIFOs of the
// test's own, rt giving every token back however it ends, -M rules, and a real make -j run.
#include <sys/stat.h>

#include <algorithm>
#include <cstring>

#include "check.h"
#include "process_util.h"
#include "batch/depfile.h"
#include "rt/error.h"
#include "common/interrupt.h"
#include "batch/jobserver.h"

using namespace rt_test;
namespace fs = std::filesystem;
using Kind = rt::JobserverAuth::Kind;

namespace {

const std::string kScene = kSmallScene;

// A pipe loaded with tokens, as make makes it; its descriptors are inherited by children.
struct TokenPipe {
    int fds[2] = {-1, -1};
    explicit TokenPipe(const std::string& tokens) {
        CHECK_EQ(::pipe(fds), 0);
        CHECK_EQ(::write(fds[1], tokens.data(), tokens.size()),
                 static_cast<ssize_t>(tokens.size()));
    }
    ~TokenPipe() {
        ::close(fds[0]);
        ::close(fds[1]);
    }
    std::string makeflags() const {
        return " -j4 --jobserver-auth=" + std::to_string(fds[0]) + "," + std::to_string(fds[1]);
    }
    // What is in the pipe now, sorted (make does not care about the order).
    std::string drain() const {
        const int flags = ::fcntl(fds[0], F_GETFL);
        ::fcntl(fds[0], F_SETFL, flags | O_NONBLOCK);
        std::string tokens;
        char c = 0;
        while (::read(fds[0], &c, 1) == 1) tokens += c;
        ::fcntl(fds[0], F_SETFL, flags);
        std::sort(tokens.begin(), tokens.end());
        return tokens;
    }
};

int hardware_threads() {
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

std::string threads_line(int threads, int tokens) {
    return "rt: " + std::to_string(threads) + (threads == 1 ? " thread, " : " threads, ") +
           std::to_string(tokens) + " jobserver tokens\n";
}

}  // namespace

TEST(makeflags_are_parsed) {
    rt::JobserverAuth a = rt::parse_makeflags(" -j4 --jobserver-auth=3,4");
    CHECK(a.kind == Kind::pipe);
    CHECK_EQ(a.read_fd, 3);
    CHECK_EQ(a.write_fd, 4);
    CHECK(!a.dry_run);
    a = rt::parse_makeflags("s -j --jobserver-fds=5,6");  // make before 4.2
    CHECK(a.kind == Kind::pipe);
    CHECK_EQ(a.read_fd, 5);
    a = rt::parse_makeflags("-j8 --jobserver-auth=fifo:/tmp/GMfifo12\\ 3");
    CHECK(a.kind == Kind::fifo);
    CHECK_EQ(a.fifo, std::string("/tmp/GMfifo12 3"));
    a = rt::parse_makeflags("--jobserver-auth=3,4 --jobserver-auth=fifo:/x");  // the last counts
    CHECK(a.kind == Kind::fifo);
    CHECK(rt::parse_makeflags(" -j --jobserver-auth=-2,-2").kind == Kind::disabled);
    CHECK(rt::parse_makeflags("").kind == Kind::none);
    CHECK(rt::parse_makeflags("k -j4").kind == Kind::none);
    CHECK(rt::parse_makeflags(" -- X=--jobserver-auth=3,4").kind == Kind::none);
    CHECK(rt::parse_makeflags("--jobserver-auth=garbage").kind == Kind::none);
    CHECK(rt::parse_makeflags("ns -j2 --jobserver-auth=3,4").dry_run);
    CHECK(!rt::parse_makeflags(" -j2 --jobserver-auth=3,4").dry_run);
    CHECK(!rt::parse_makeflags("--no-print-directory").dry_run);
    // make -q (question) and -t (touch) run '+' lines too, and mean nothing is to be made.
    CHECK(rt::parse_makeflags("q -- N=4").dry_run);
    CHECK(rt::parse_makeflags("st").dry_run);
    CHECK(!rt::parse_makeflags("s -j2").dry_run);
}

TEST(the_client_takes_free_tokens_and_gives_the_same_back) {
    const TokenPipe pipe("abc");
    rt::JobserverAuth auth = rt::parse_makeflags(pipe.makeflags());
    {
        rt::JobserverClient client(auth);
        CHECK(client.usable());
        CHECK_EQ(client.acquire(2), 2);
        CHECK_EQ(rt::interrupt::tokens_held(), 2);
        CHECK_EQ(pipe.drain().size(), 1u);  // one left (and now taken out by the test)
        client.release();
        CHECK_EQ(rt::interrupt::tokens_held(), 0);
        CHECK_EQ(pipe.drain().size(), 2u);
        CHECK_EQ(client.acquire(5), 0);  // none free: no waiting
    }
    // The destructor gives back what is held.
    const TokenPipe full("xyz");
    {
        rt::JobserverClient client(rt::parse_makeflags(full.makeflags()));
        CHECK_EQ(client.acquire(10), 3);
    }
    CHECK_EQ(full.drain(), std::string("xyz"));
}

TEST(the_client_uses_a_fifo) {
    const fs::path dir = work_dir("fifo_jobserver");
    const fs::path fifo = dir / "jobserver";
    CHECK_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const int keep = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);  // make's end
    CHECK_EQ(::write(keep, "++", 2), 2);
    {
        rt::JobserverClient client(
            rt::parse_makeflags("-j3 --jobserver-auth=fifo:" + fifo.string()));
        CHECK(client.usable());
        CHECK_EQ(client.acquire(8), 2);
    }
    char back[4] = {};
    CHECK_EQ(::read(keep, back, sizeof back), 2);
    CHECK_EQ(std::string(back), std::string("++"));
    ::close(keep);
    rt::JobserverClient missing(
        rt::parse_makeflags("--jobserver-auth=fifo:" + (dir / "no").string()));
    CHECK(!missing.usable());
    CHECK_CONTAINS(missing.problem(), "is missing");
}

TEST(closed_descriptors_are_reported) {
    int fds[2];
    CHECK_EQ(::pipe(fds), 0);
    ::close(fds[0]);
    ::close(fds[1]);
    rt::JobserverClient client(rt::parse_makeflags("--jobserver-auth=" + std::to_string(fds[0]) +
                                                   "," + std::to_string(fds[1])));
    CHECK(!client.usable());
    CHECK_CONTAINS(client.problem(), "mark rt's recipe line with '+'");
    // Two descriptors that are not one pipe's ends are refused too.
    const TokenPipe a("a"), b("b");
    rt::JobserverClient mixed(rt::parse_makeflags("--jobserver-auth=" + std::to_string(a.fds[0]) +
                                                  "," + std::to_string(b.fds[1])));
    CHECK(!mixed.usable());
}

TEST(rt_takes_tokens_and_gives_every_one_back) {
    const fs::path dir = work_dir("rt_tokens");
    write_file(dir / "scene.in", kScene);
    write_file(dir / "bad.in", "102 0 0 5\n");
    const TokenPipe pipe("abc");
    SpawnOptions options;
    options.env = {"MAKEFLAGS=" + pipe.makeflags(), "RT_DEBUG=threads"};
    const int tokens = std::min(3, hardware_threads() - 1);
    RunResult r = run_rt_args(dir, {"scene.in", "-o", "out.ppm"}, options);
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err, threads_line(1 + tokens, tokens));
    CHECK_EQ(pipe.drain(), std::string("abc"));
    CHECK_EQ(::write(pipe.fds[1], "abc", 3), 3);
    // An error after the tokens were taken.
    r = run_rt_args(dir, {"bad.in", "-o", "out.ppm"}, options);
    CHECK_EQ(r.status, 1);
    CHECK_EQ(pipe.drain(), std::string("abc"));
    CHECK_EQ(::write(pipe.fds[1], "abc", 3), 3);
    // -j N: no tokens are taken.
    r = run_rt_args(dir, {"-j", "2", "scene.in", "-o", "out.ppm"}, options);
    CHECK_EQ(r.err, threads_line(2, 0));
    // make -n: rt does nothing at all.
    options.env[0] = "MAKEFLAGS=n" + pipe.makeflags();
    fs::remove(dir / "out.ppm");
    r = run_rt_args(dir, {"scene.in", "-o", "out.ppm"}, options);
    CHECK_EQ(r.status, 0);
    CHECK(!fs::exists(dir / "out.ppm"));
    // A signal mid-render.
    write_file(dir / "slow.in", kSlowScene);
    options.env[0] = "MAKEFLAGS=" + pipe.makeflags();
    const pid_t pid = spawn_rt(dir, {"-s", "8", "slow.in", "-o", "slow.ppm"}, options);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (read_file(dir / "rt.err").empty() && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ::kill(pid, SIGTERM);
    const int status = wait_for(pid);
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
    CHECK_EQ(pipe.drain(), std::string("abc"));
}

TEST(make_rules_are_escaped) {
    CHECK_EQ(rt::make_escape("plain/path.ppm"), std::string("plain/path.ppm"));
    CHECK_EQ(rt::make_escape("a b#c$d:e"), std::string("a\\ b\\#c$$d\\:e"));
    CHECK_EQ(rt::make_escape("w*?[1]"), std::string("w\\*\\?\\[1]"));
    CHECK_EQ(rt::make_escape("x\\ y"), std::string("x\\\\\\ y"));
    CHECK_EQ(rt::make_escape("x\\y"), std::string("x\\y"));
    CHECK_EQ(rt::make_escape("end\\"), std::string("end\\\\"));
    bool threw = false;
    try {
        rt::make_escape("100%.ppm");
    } catch (const rt::Error&) {
        threw = true;
    }
    CHECK(threw);
    CHECK_EQ(rt::make_rule("out.ppm", {"s.in", "t x.ppm"}),
             std::string("out.ppm: \\\n  s.in \\\n  t\\ x.ppm\n\ns.in:\n\nt\\ x.ppm:\n"));
}

TEST(depend_option_writes_a_rule_after_the_image) {
    const fs::path dir = work_dir("depend");
    fs::create_directories(dir / "tex dir");
    write_file(dir / "tex dir/t$1.ppm", "P3\n1 1\n255\n1 2 3\n");
    write_file(dir / "scene.in",
               kScene +
                   "1 .5 0 0 0 108 0 0 0 1 0 0 0 1 0 \"tex dir/t$1.ppm\" 100 1 1 1 .5 10 0 0 1\n"
                   "1 .5 2 0 0 108 0 0 0 1 0 0 0 1 0 \"tex dir/t$1.ppm\" 100 1 1 1 .5 10 0 0 1\n");
    RunResult r = run_rt(dir, "scene.in -o out.ppm -M out.d");
    CHECK_EQ(r.status, 0);
    CHECK_EQ(read_file(dir / "out.d"),
             std::string("out.ppm: \\\n  scene.in \\\n  tex\\ dir/t$$1.ppm\n\nscene.in:\n\n"
                         "tex\\ dir/t$$1.ppm:\n"));
    // A failed render writes no rule, and leaves the old one.
    write_file(dir / "bad.in", "102 0 0 5\n");
    r = run_rt(dir, "bad.in -o bad.ppm -M out.d");
    CHECK_EQ(r.status, 1);
    CHECK(read_file(dir / "out.d").find("scene.in") != std::string::npos);
    for (const char* args : {"-M x.d scene.in", "-r -M x.d scene.in",
                             "-M out.ppm -o out.ppm scene.in", "-M - -o o.ppm scene.in"}) {
        r = run_rt(dir, args);
        CHECK_EQ(r.status, 2);
    }
    r = run_rt(dir, "-M scene.in -o o.ppm scene.in");
    CHECK_EQ(r.status, 1);
    CHECK_CONTAINS(r.err, "scene.in: cannot write the dependency rule: it is the scene file");
}

// A real make -j: every rt takes what tokens are free and gives them back (make says
// "INTERNAL: Exiting with N jobserver tokens" otherwise), and -M makes a changed texture
// re-render only the frames that use it.
TEST(a_real_make_with_its_jobserver) {
    if (!on_path("make")) return;  // make is not installed
    const fs::path dir = work_dir("make");
    write_file(dir / "tex.ppm", "P3\n1 1\n255\n1 2 3\n");
    for (int i = 1; i <= 4; ++i) write_file(dir / join("f", i, ".in"), kScene);
    write_file(dir / "f4.in",
               kScene + "1 .5 0 0 0 108 0 0 0 1 0 0 0 1 0 tex.ppm 100 1 1 1 .5 10 0 0 1\n");
    write_file(dir / "Makefile",
               "FRAMES := f1.ppm f2.ppm f3.ppm f4.ppm\n"
               "all: $(FRAMES)\n"
               "%.ppm: %.in\n"
               "\t+@RT_DEBUG=threads '" RT_BINARY
               "' -M $*.d $< -o $@\n"
               "-include $(FRAMES:.ppm=.d)\n");
    const std::string make = "cd '" + dir.string() + "' && make -j3 >make.out 2>make.err";
    CHECK_EQ(std::system(make.c_str()), 0);
    std::string err = read_file(dir / "make.err");
    CHECK(err.find("INTERNAL") == std::string::npos);
    CHECK(err.find("warning") == std::string::npos);
    CHECK_CONTAINS(err, "jobserver tokens");
    for (int i = 1; i <= 4; ++i) CHECK(fs::exists(dir / join("f", i, ".ppm")));
    // A newer texture: only f4 is made again.
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    write_file(dir / "tex.ppm", "P3\n1 1\n255\n3 2 1\n");
    CHECK_EQ(std::system(make.c_str()), 0);
    err = read_file(dir / "make.err");
    CHECK_EQ(std::count(err.begin(), err.end(), '\n'), 1);
    // A deleted texture that the scene no longer names does not stop make: its empty rule.
    fs::remove(dir / "tex.ppm");
    write_file(dir / "f4.in", kScene);
    CHECK_EQ(std::system(make.c_str()), 0);
}
