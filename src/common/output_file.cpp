#include "common/output_file.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "common/interrupt.h"
#include "rt/error.h"

namespace rt {

namespace {

// The suffix of temporary files: "NAME.tmp-XXXXXX", XXXXXX filled in by mkstemp.
constexpr std::string_view kTemporarySuffix = ".tmp-XXXXXX";
// More symlinks than this in a row is a loop (Linux's own limit).
constexpr int kMaxLinkHops = 40;

std::string parent_dir(const std::string& path) {
    const std::string parent = std::filesystem::path(path).parent_path().string();
    return parent.empty() ? "." : parent;
}

std::string octal_mode(mode_t mode) {
    char text[16];
    std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode & 07777));
    return text;
}

bool same_file(const struct stat& a, const struct stat& b) {
    return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

// Follows symlinks from `path` to the name they end at, which need not exist yet (a dangling
// link is followed, so the file is created where the link points). Returns "" for a loop.
std::string resolve_links(std::string path) {
    for (int hop = 0; hop < kMaxLinkHops; ++hop) {
        struct stat st {};
        if (::lstat(path.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return path;
        std::vector<char> buffer(PATH_MAX + 1);
        const ssize_t n = ::readlink(path.c_str(), buffer.data(), buffer.size());
        if (n < 0 || static_cast<std::size_t>(n) >= buffer.size()) return path;
        const std::string target(buffer.data(), static_cast<std::size_t>(n));
        path = target.front() == '/' ? target : parent_dir(path) + "/" + target;
    }
    return "";
}

// A temporary name beside `target` that fits the directory's name limit: the base name is
// shortened (at a UTF-8 character boundary) when the suffix would not fit.
std::string temporary_template(const std::string& dir, const std::string& base) {
    long name_max = ::pathconf(dir.c_str(), _PC_NAME_MAX);
    if (name_max <= 0) name_max = NAME_MAX;
    std::string kept = base;
    const auto room = static_cast<std::size_t>(name_max) - kTemporarySuffix.size();
    if (kept.size() > room) {
        std::size_t cut = room;
        while (cut > 0 && (static_cast<unsigned char>(kept[cut]) & 0xC0) == 0x80) --cut;
        kept.resize(cut);
    }
    return dir + "/" + kept + std::string(kTemporarySuffix);
}

}  // namespace

void OutputFile::fail(const std::string& why) const {
    throw Error((path_ == "-" ? std::string("<stdout>") : path_) + ": cannot write " + what_ +
                ": " + why);
}

OutputFile::OutputFile(std::string path, const std::vector<InputFile>& inputs, std::string what,
                       std::string reader)
    : path_(std::move(path)), what_(std::move(what)), reader_(std::move(reader)) {
    if (path_ == "-") {
        struct stat st {};
        if (::fstat(STDOUT_FILENO, &st) != 0) fail("standard output is closed");
        if (::isatty(STDOUT_FILENO))
            fail(
                "standard output is a terminal, and rt does not write binary data to one: "
                "redirect it (rt scene.in > image.ppm) or use -o FILE");
        refuse_inputs(st, inputs);
        fd_ = STDOUT_FILENO;
        return;
    }
    struct stat st {};
    if (::stat(path_.c_str(), &st) != 0) {
        const int error = errno;
        if (error != ENOENT) fail(std::strerror(error));
        // A new name, or a symlink to one: created where the link points.
        const std::string target = resolve_links(path_);
        if (target.empty()) fail(std::strerror(ELOOP));
        prepare_replacement(target, nullptr);
        return;
    }
    if (S_ISDIR(st.st_mode)) fail("it is a directory: name a file in it (-o DIR/image.ppm)");
    refuse_inputs(st, inputs);
    if (S_ISREG(st.st_mode)) {
        // A symlink's target is replaced. A /proc/self/fd link may lead to no name at all (a
        // deleted file): that file is written in place.
        const std::string target = resolve_links(path_);
        struct stat resolved {};
        if (!target.empty() && ::stat(target.c_str(), &resolved) == 0 && same_file(resolved, st)) {
            prepare_replacement(target, &st);
        } else {
            truncate_ = true;
            open_in_place();
        }
    } else if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode)) {
        open_in_place();
    } else if (S_ISBLK(st.st_mode)) {
        fail(
            "it is a block device (a disk); rt writes to files, character devices, FIFOs and "
            "sockets only");
    } else {
        fail("it is not a file, a character device, a FIFO or a socket");
    }
}

void OutputFile::refuse_inputs(const struct stat& st, const std::vector<InputFile>& inputs) {
    for (const InputFile& input : inputs) {
        struct stat input_st {};
        if (input.path.empty() || ::stat(input.path.c_str(), &input_st) != 0 ||
            !same_file(st, input_st))
            continue;
        fail("it is " + input.role + " '" + input.path.string() + "', which " + reader_ +
             " reads: choose another name");
    }
}

// Devices, FIFOs and sockets are written where they are: replacing one would destroy it.
void OutputFile::open_in_place() {
    struct stat st {};
    if (::stat(path_.c_str(), &st) == 0 && S_ISSOCK(st.st_mode)) {
        sockaddr_un address{};
        address.sun_family = AF_UNIX;
        if (path_.size() >= sizeof address.sun_path)
            fail("the socket's name is too long to connect to");
        std::memcpy(address.sun_path, path_.c_str(), path_.size() + 1);
        fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (fd_ < 0) fail(std::strerror(errno));
        own_fd_ = true;
        if (::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0)
            fail(std::string("cannot connect to the socket: ") + std::strerror(errno));
        return;
    }
    // A FIFO blocks here until a reader opens it, as a shell redirect does.
    fd_ = ::open(path_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd_ < 0) fail(std::strerror(errno));
    own_fd_ = true;
    if (::isatty(fd_))
        fail("it is a terminal, and rt does not write binary data to one: name a file instead");
}

void OutputFile::prepare_replacement(const std::string& target, const struct stat* existing) {
    const std::string base = std::filesystem::path(target).filename().string();
    if (base.empty() || base == "." || base == "..") fail("it names a directory, not a file");
    const std::string dir = parent_dir(target);
    struct stat dir_st {};
    if (::stat(dir.c_str(), &dir_st) != 0) {
        if (errno == ENOENT) fail("the directory '" + dir + "' does not exist");
        fail("cannot use the directory '" + dir + "': " + std::strerror(errno));
    }
    if (!S_ISDIR(dir_st.st_mode)) fail("'" + dir + "' is not a directory");
    const bool root = ::geteuid() == 0;
    if (existing != nullptr) {
        // As a shell redirect would: only a file the user may write is replaced. (access()
        // lets root write any file, as a redirect does, except on a read-only file system.)
        if (::access(target.c_str(), W_OK) != 0) {
            if (errno == EROFS) fail("it is on a read-only file system");
            fail("the file is write-protected (mode " + octal_mode(existing->st_mode) +
                 "): make it writable (chmod u+w '" + target + "') or choose another name");
        }
        if (existing->st_nlink > 1)
            fail("the file has " + std::to_string(existing->st_nlink) +
                 " hard links, and rt neither splits them (replacing one name) nor writes "
                 "through all of them: remove it first (rm '" +
                 target + "') or choose another name");
        if ((dir_st.st_mode & S_ISVTX) && !root && existing->st_uid != ::geteuid() &&
            dir_st.st_uid != ::geteuid())
            fail("the directory '" + dir +
                 "' has the sticky bit set (like /tmp) and the file belongs to another user, "
                 "so only they may replace it: choose another name");
    }
    if (::access(dir.c_str(), W_OK | X_OK) != 0) {
        if (errno == EROFS) fail("it is on a read-only file system");
        fail("the directory '" + dir + "' is not writable (" + std::strerror(errno) +
             "): rt writes a temporary file there and renames it over the old one only once "
             "it is complete; choose a directory you may write");
    }
    std::string name = temporary_template(dir, base);
    {
        // The file is registered for removal before any signal can end rt.
        const interrupt::SignalsBlocked blocked;
        fd_ = ::mkstemp(name.data());
        if (fd_ < 0)
            fail("cannot create a temporary file in '" + dir + "': " + std::strerror(errno));
        own_fd_ = true;
        temporary_ = name;
        cleanup_slot_ = interrupt::register_temporary(temporary_);
    }
    ::fcntl(fd_, F_SETFD, FD_CLOEXEC);
    mode_t mode = 0;
    if (existing != nullptr) {
        // Keep the owner and group where permitted; a group that cannot be kept gets no
        // access, so a file shared with one group is never opened to another.
        mode = existing->st_mode & 0777;
        if (::fchown(fd_, existing->st_uid, existing->st_gid) != 0 &&
            ::fchown(fd_, static_cast<uid_t>(-1), existing->st_gid) != 0)
            mode &= ~static_cast<mode_t>(070);
    } else {
        // What a shell redirect would create: 0666 less the umask.
        const mode_t mask = ::umask(0);
        ::umask(mask);
        mode = 0666 & ~mask;
    }
    if (::fchmod(fd_, mode) != 0) fail(std::string("cannot set its mode: ") + std::strerror(errno));
    target_ = target;
}

OutputFile::~OutputFile() {
    if (own_fd_ && fd_ >= 0) ::close(fd_);
    if (!temporary_.empty()) {
        ::unlink(temporary_.c_str());
        interrupt::forget_temporary(cleanup_slot_);
    }
}

void OutputFile::write_bytes(std::string_view bytes) {
    append(bytes);
    commit();
}

void OutputFile::append(std::string_view bytes) {
    if (committed_ || fd_ < 0) fail("it was written already");
    if (!started_ && truncate_ && ::ftruncate(fd_, 0) != 0) fail(std::strerror(errno));
    started_ = true;
    while (!bytes.empty()) {
        const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) fail(std::strerror(errno));
        bytes.remove_prefix(static_cast<std::size_t>(n));
    }
}

void OutputFile::commit() {
    if (committed_ || fd_ < 0) fail("it was written already");
    if (!started_ && truncate_ && ::ftruncate(fd_, 0) != 0) fail(std::strerror(errno));
    if (!temporary_.empty()) {
        // On disk before the rename, so that a crash leaves the old file or the new, whole.
        if (::fsync(fd_) != 0) fail(std::strerror(errno));
        const int fd = fd_;
        fd_ = -1;
        if (::close(fd) != 0) fail(std::strerror(errno));
        if (::rename(temporary_.c_str(), target_.c_str()) != 0) fail(std::strerror(errno));
        interrupt::forget_temporary(cleanup_slot_);
        temporary_.clear();
    } else if (own_fd_) {
        const int fd = fd_;
        fd_ = -1;
        if (::close(fd) != 0) fail(std::strerror(errno));
    }
    committed_ = true;
}

}  // namespace rt
