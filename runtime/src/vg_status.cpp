// Status strings and version numbers.
#include "vorogeo.h"
#include "vorogeo_container.h"

extern "C" const char* vg_status_string(vg_status status) {
    switch (status) {
    case VG_OK: return "ok";
    case VG_ERR_INVALID_ARGUMENT: return "invalid argument (NULL pointer, zero size or value out of range)";
    case VG_ERR_BUFFER_TOO_SMALL: return "caller memory is smaller than the size query returned";
    case VG_ERR_TRUNCATED: return "blob is truncated (shorter than its header says)";
    case VG_ERR_BAD_MAGIC: return "not a vorogeo blob (bad magic)";
    case VG_ERR_UNSUPPORTED_VERSION: return "unsupported blob format version";
    case VG_ERR_UNSUPPORTED_FLAGS: return "unsupported blob flags (or compressed blob in a build without zstd)";
    case VG_ERR_CHECKSUM: return "blob checksum mismatch (corrupted payload)";
    case VG_ERR_DECOMPRESSION: return "blob payload does not decompress to the stated size";
    case VG_ERR_CORRUPT_STRUCTURE: return "blob structure is corrupt (flatbuffer verification or sizes)";
    case VG_ERR_CORRUPT_CONTENT: return "blob content is inconsistent (index out of range or counts disagree)";
    case VG_ERR_INVALID_VERTEX: return "vertex id out of range";
    case VG_ERR_WRONG_WORKSPACE: return "workspace belongs to another graph";
    case VG_ERR_IO: return "cannot open, read or map the file";
    case VG_ERR_OUT_OF_MEMORY: return "allocator returned NULL";
    case VG_ERR_NO_SLICED_QUERY: return "no time-sliced query in progress on this workspace (none begun, or another query abandoned it)";
    case VG_ERR_INVALID_POINT: return "invalid surface point (face out of range, or barycentric weights NaN, negative or not summing to 1)";
    case VG_ERR_PATH_FAILED: return "path tracing failed (a defect: please report the blob and points)";
    case VG_ERR_NO_HUB_LABELS: return "the graph has no hub labels (bake with --hub-labels)";
    }
    return "unknown status";
}

extern "C" const char* vg_version_string(void) { return VG_VERSION_STRING; }

extern "C" unsigned vg_version_number(void) { return VG_VERSION_NUMBER; }

extern "C" unsigned vg_blob_format_version(void) { return VG_FORMAT_VERSION; }

static_assert(VG_BLOB_FORMAT_VERSION == VG_FORMAT_VERSION, "public and container format versions differ");
static_assert(VG_VERSION_MAJOR == VG_VERSION_MAJOR_ && VG_VERSION_MINOR == VG_VERSION_MINOR_ &&
                  VG_VERSION_PATCH == VG_VERSION_PATCH_,
              "vorogeo.h's version macros differ from the CMake project version");
