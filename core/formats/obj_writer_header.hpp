// The comment line in which write_obj gives the world origin and read_obj takes it back
// (internal to cullcheck_formats). OBJ has no place for metadata but comments.
#pragma once

namespace cullcheck::formats::detail {

// Followed by the origin's x and y, in metres, as 17 significant digits.
inline constexpr const char* kObjOriginComment = "# cullcheck origin:";

}  // namespace cullcheck::formats::detail
