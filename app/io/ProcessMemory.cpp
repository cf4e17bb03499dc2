/// \file ProcessMemory.cpp
/// Resident memory from /proc (see ProcessMemory.h).

#include "app/io/ProcessMemory.h"

#include <unistd.h>

#include <cstdio>
#include <cstring>

namespace gale::app {

double residentBytes() {
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0.0;
    unsigned long long sizePages = 0, residentPages = 0;
    const int got = std::fscanf(f, "%llu %llu", &sizePages, &residentPages);
    std::fclose(f);
    const long page = ::sysconf(_SC_PAGESIZE);
    return got == 2 && page > 0 ? double(residentPages) * double(page) : 0.0;
}

double peakResidentBytes() {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0.0;
    char line[256];
    double bytes = 0.0;
    while (std::fgets(line, sizeof line, f)) {
        unsigned long long kib = 0;
        if (std::strncmp(line, "VmHWM:", 6) == 0 && std::sscanf(line + 6, "%llu", &kib) == 1) {
            bytes = double(kib) * 1024.0;
            break;
        }
    }
    std::fclose(f);
    return bytes;
}

}  // namespace gale::app
