#pragma once
// Model files checked before assimp reads them, where assimp 5.2.5 (Debian 12) would crash,
// allocate without bound, or refuse the file without naming the line: each check throws
// sl::Error naming the file, the line and what is wrong, and what is allowed.

#include <filesystem>

namespace sl {

// An OBJ file's face, line and point indices: a position index must name one of the file's `v`
// lines (1..n, or -1..-k for the k read so far), likewise texture coordinates (`vt`) and normals
// (`vn`). assimp refuses such a file too, but names no line, and its OBJ importer leaks the mesh
// it was building when it throws (assimp issue #4131, fixed in 5.4.2; tests/fuzz/lsan.supp covers
// the cases its parser reads differently from this one). Tokens that are not integers are left to
// assimp's parser.
void check_obj_indices(const std::filesystem::path& path);

// A PLY file's header: its format, element counts and property types. assimp reserves memory for
// the counts the header declares before it reads a byte of data (a count of 4e9 is a bad_alloc, one
// of 2e8 takes 3 GiB and 14 s to find the file corrupt), so a count beyond the mesh limits of
// scenes/mesh.h, or less data than the counts need (walked item by item in binary files, at least
// a number per property in ASCII ones), is refused here.
void check_ply_header(const std::filesystem::path& path);

}  // namespace sl
