/* vorogeo runtime: fast approximate geodesic distances on a baked triangle mesh.
 *
 * C99 API. Every function is thread-safe unless documented otherwise; the
 * library never allocates memory and never throws. */
#ifndef VOROGEO_H
#define VOROGEO_H

#ifdef __cplusplus
extern "C" {
#endif

/* Status codes returned by every fallible call. 0 is success. */
typedef enum vg_status {
    VG_OK = 0,
    VG_ERR_INVALID_ARGUMENT = 1
} vg_status;

/* Human-readable, static, never NULL. Unknown codes give "unknown status". */
const char* vg_status_string(vg_status status);

/* Library version, for example "0.1.0"; static storage. */
const char* vg_version_string(void);
/* Library version as (major << 16) | (minor << 8) | patch. */
unsigned vg_version_number(void);

#ifdef __cplusplus
}
#endif

#endif /* VOROGEO_H */
