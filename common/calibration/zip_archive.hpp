#pragma once
// Entries of a zip archive held in memory, through libzip (an MPCDI package is a flat zip, VESA
// MPCDI v2.0 (2015)). Every error is a CalibrationError naming the archive and the entry.
#include <string>

struct zip;

namespace cupola {

class ZipArchive {
public:
    // Opens the archive in `bytes` (kept by reference: it must outlive this object).
    ZipArchive(const std::string& bytes, const std::string& name);
    ~ZipArchive();
    ZipArchive(const ZipArchive&) = delete;
    ZipArchive& operator=(const ZipArchive&) = delete;

    bool contains(const std::string& entry) const;
    // The entry's bytes (found by exact name, else ignoring case); at most 512 MiB.
    std::string read(const std::string& entry) const;

private:
    std::string name_;
    ::zip* archive_ = nullptr;
    long long locate(const std::string& entry) const;
};

}  // namespace cupola
