// rt's side of the line-marker contract (`#line N "path"` alone on its line renames the next
// line) and the note that an error at an object ID adds about the object before it.
#include <string>

#include "check.h"
#include "scene_util.h"

using rt_test::kTestViewer;
using rt_test::scene_error;

namespace {
const std::string kBadSphere = "1 -1 0 0 0 100 1 1 1 0 1 1 0 1\n";
}

TEST(a_marker_names_the_next_line_and_file) {
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) + "#line 40 \"scene.rts\"\n" + kBadSphere),
                   "scene.rts:40:3: sphere radius must be > 0, got -1");
    // Lines after the marked one count on from it; blanks around the marker are allowed.
    CHECK_CONTAINS(
        scene_error(std::string(kTestViewer) + "  #line 7 \"a b.rts\"  \r\n\n\n" + kBadSphere),
        "a b.rts:9:3: sphere radius must be > 0");
    // A later marker may return to the input's own name.
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) +
                               "#line 3 \"x.rts\"\n#line 12 \"test.in\"\n" + kBadSphere),
                   "test.in:12:3:");
}

TEST(malformed_markers_are_only_comments) {
    const char* malformed[] = {
        "#line 0 \"x.rts\"", "#line -3 \"x.rts\"", "#line 5",
        "#line 5 x.rts",     "#line 5 \"\"",       "#line 5 \"x.rts\" extra",
        "#line5 \"x.rts\"",  "# line 5 \"x.rts\"", "#line 99999999999 \"x.rts\"",
        "#line 5 \"x.rts",   "#LINE 5 \"x.rts\"",  "#line 5.5 \"x.rts\"",
    };
    for (const char* marker : malformed)
        CHECK_CONTAINS(scene_error(std::string(kTestViewer) + marker + "\n" + kBadSphere),
                       "test.in:3:3: sphere radius must be > 0");
    // A marker after a token on the same line is a comment too.
    CHECK_CONTAINS(
        scene_error(std::string(kTestViewer) + "103 0 0 0 #line 40 \"x.rts\"\n" + kBadSphere),
        "test.in:3:3:");
    // A marker longer than any token is refused as a marker, not an error.
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) + "#line 4 \"" + std::string(5000, 'a') +
                               "\"\n" + kBadSphere),
                   "test.in:3:3:");
}

TEST(a_marker_applies_to_every_error_after_it) {
    // End of file, and the missing-viewer error at the end, are named in the marked file.
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) + "#line 20 \"s.rts\"\n1 1 0 0"),
                   "s.rts:20:8: unexpected end of file");
    CHECK_CONTAINS(scene_error("#line 5 \"s.rts\"\n103 1 1 1\n"), "s.rts:5:10: no viewer");
}

TEST(an_error_at_an_object_id_notes_the_object_before_it) {
    // A surface with one number too many: the extra number is read as the next object's ID.
    const std::string scene = std::string(kTestViewer) +
                              "1 1 0 0 0\n"
                              "  100 1 1 1 0 1 1 0 1 0.5\n";
    const std::string error = scene_error(scene);
    CHECK_CONTAINS(error, "test.in:3:23: object ID must be a whole number, got 0.5\n");
    CHECK_CONTAINS(error,
                   "test.in:3:23: note: the previous object, simple surface 100 at 3:3, read 8 "
                   "numbers ending at 3:21, within sphere 1 at 2:1 (13 numbers in all)");
    // An unknown ID and a surface at the top level get the note too.
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) + "103 1 1 1 42\n"),
                   "note: the previous object, ambient light 103 at 2:1, read 3 numbers ending "
                   "at 2:9");
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) + "103 1 1 1 100\n"),
                   "note: the previous object, ambient light 103");
    // No note before the first object, where there is no previous one.
    CHECK(scene_error("42\n").find("note:") == std::string::npos);
    // The note names the previous object's file when a marker moved the error to another.
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) + "103 1 1 1\n#line 9 \"b.rts\"\nx\n"),
                   "b.rts:9:1: note: the previous object, ambient light 103 at test.in:2:1");
}

TEST(a_marker_path_with_a_control_byte_is_only_a_comment) {
    // Found by fuzzing: the path would be printed in every message after it.
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) + "#line 20 \"s\x1b[2J\"\n1 1 0 0"),
                   "test.in:3:8: unexpected end of file");
    CHECK_CONTAINS(scene_error(std::string(kTestViewer) + "#line 20 \"s" + std::string(1, '\0') +
                               "x\"\n1 1 0 0"),
                   "test.in:3:8: unexpected end of file");
}
