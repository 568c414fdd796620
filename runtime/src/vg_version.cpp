#include "vorogeo.h"

extern "C" const char* vg_status_string(vg_status status) {
    switch (status) {
    case VG_OK: return "ok";
    case VG_ERR_INVALID_ARGUMENT: return "invalid argument";
    }
    return "unknown status";
}

extern "C" const char* vg_version_string(void) { return VG_VERSION_STRING; }

extern "C" unsigned vg_version_number(void) {
    return (VG_VERSION_MAJOR_ << 16) | (VG_VERSION_MINOR_ << 8) | VG_VERSION_PATCH_;
}
