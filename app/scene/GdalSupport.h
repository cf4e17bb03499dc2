#pragma once
/// \file GdalSupport.h
/// What every GDAL reader and writer of app/scene shares (Dem.cpp, ProbePoints.cpp): GDAL's own
/// printing silenced while a call runs, its last message as one line, datasets closed by scope.
/// Include only from .cpp files that call GDAL (compile time).

#include <cpl_error.h>
#include <gdal_priv.h>

#include <memory>
#include <string>

namespace gale::app {

/// GDAL's last error message, one line ("unknown error" when it said nothing).
inline std::string gdalMessage() {
    std::string s = CPLGetLastErrorMsg();
    s = s.substr(0, s.find('\n'));
    return s.empty() ? "unknown error" : s;
}

/// Silences GDAL's own printing for its lifetime; errors are read with gdalMessage().
class QuietGdal {
  public:
    QuietGdal() {
        CPLPushErrorHandler(CPLQuietErrorHandler);
        CPLErrorReset();
    }
    ~QuietGdal() { CPLPopErrorHandler(); }
    QuietGdal(const QuietGdal&) = delete;
    QuietGdal& operator=(const QuietGdal&) = delete;
};

struct DatasetCloser {
    void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
/// A dataset closed when it goes out of scope.
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

}  // namespace gale::app
