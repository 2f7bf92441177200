#include "calibration/zip_archive.hpp"

#include <zip.h>

#include "calibration/calibration_error.hpp"

namespace cupola {

namespace {
constexpr size_t max_entry_bytes = size_t(512) << 20;

}  // namespace

ZipArchive::ZipArchive(const std::string& bytes, const std::string& name) : name_(name) {
    zip_error_t error;
    zip_error_init(&error);
    zip_source_t* src = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
    if (src) archive_ = zip_open_from_source(src, ZIP_RDONLY, &error);
    if (!archive_) {
        const std::string why = zip_error_strerror(&error);
        if (src) zip_source_free(src);
        zip_error_fini(&error);
        throw CalibrationError(name, "zip", "not a readable zip archive: " + why);
    }
    zip_error_fini(&error);
}

ZipArchive::~ZipArchive() {
    if (archive_) zip_discard(archive_);
}

long long ZipArchive::locate(const std::string& entry) const {
    zip_int64_t i = zip_name_locate(archive_, entry.c_str(), 0);
    if (i < 0) i = zip_name_locate(archive_, entry.c_str(), ZIP_FL_NOCASE);
    return i;
}

bool ZipArchive::contains(const std::string& entry) const { return locate(entry) >= 0; }

std::string ZipArchive::read(const std::string& entry) const {
    const zip_int64_t index = locate(entry);
    if (index < 0) throw CalibrationError(name_, entry, "missing from the package");
    zip_file_t* f = zip_fopen_index(archive_, static_cast<zip_uint64_t>(index), 0);
    if (!f) throw CalibrationError(name_, entry, std::string("cannot open in the zip: ") + zip_strerror(archive_));
    std::string out;
    char chunk[65536];
    for (;;) {
        const zip_int64_t n = zip_fread(f, chunk, sizeof chunk);
        if (n < 0) {
            const std::string why = zip_file_strerror(f);
            zip_fclose(f);
            throw CalibrationError(name_, entry, "cannot read from the zip: " + why);
        }
        if (n == 0) break;
        if (out.size() + static_cast<size_t>(n) > max_entry_bytes) {
            zip_fclose(f);
            throw CalibrationError(name_, entry, "larger than 512 MiB");
        }
        out.append(chunk, static_cast<size_t>(n));
    }
    zip_fclose(f);
    return out;
}

}  // namespace cupola
