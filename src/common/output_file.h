// Where rt writes a file it makes (the image, a -M rule): safely, whatever the name is.
#pragma once

#include <sys/stat.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace rt {

// A file the program reads, which its output must not replace: `role` names it in the
// message ("the scene file", "the texture", "the input image").
struct InputFile {
    std::filesystem::path path;
    std::string role;
};

// Every check that can fail happens in the constructor, before rendering (docs/cli.md, FILES
// AND SAFETY, says what each case does and why):
// - "-" is standard output, written in place; refused when it is a terminal.
// - A regular file (or a new name) is replaced atomically: the data goes to a temporary file
//   beside it, renamed over it once complete, with the old file's mode (and owner where
//   permitted). A symlink is followed: its target is replaced, the link stays. A file the
//   user may not write (access(2) W_OK, as a shell redirect) and a file with more than one
//   hard link are refused.
// - A character device, FIFO or socket is opened and written in place, never replaced; a
//   terminal is refused.
// - A file that is one of `inputs` (the scene, its textures) is refused; an empty path is
//   none (the scene read from standard input).
// `what` names the data in messages ("the image"), `reader` the program that reads the
// inputs ("this render", "rtimg"). Throws rt::Error saying why and what to do.
class OutputFile {
  public:
    explicit OutputFile(std::string path, const std::vector<InputFile>& inputs = {},
                        std::string what = "the image", std::string reader = "this render");
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    // Writes the whole file and commits it: renames the temporary file over the target, or
    // finishes writing in place. Call it once.
    void write_bytes(std::string_view bytes);
    // Or in pieces: append them in order, then commit once. A regular file is still replaced
    // only by commit(); what is written in place (a FIFO, standard output) goes out as it
    // comes.
    void append(std::string_view bytes);
    void commit();

  private:
    void open_in_place();
    void prepare_replacement(const std::string& target, const struct stat* existing);
    void refuse_inputs(const struct stat& st, const std::vector<InputFile>& inputs);
    [[noreturn]] void fail(const std::string& why) const;

    std::string path_;  // as the user gave it
    std::string what_;
    std::string reader_;
    std::string target_;     // symlinks resolved: the name the temporary file replaces
    std::string temporary_;  // empty when writing in place
    int fd_ = -1;
    bool own_fd_ = false;    // false for standard output
    bool truncate_ = false;  // a regular file written in place (through /proc/self/fd)
    int cleanup_slot_ = -1;  // the temporary file's registration with rt::interrupt
    bool committed_ = false;
    bool started_ = false;  // something was appended
};

}  // namespace rt
