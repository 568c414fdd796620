#include "timing.h"

#include <sys/resource.h>

namespace vorogeo::tools {

double peakRssMb() {
    struct rusage usage {};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

}  // namespace vorogeo::tools
