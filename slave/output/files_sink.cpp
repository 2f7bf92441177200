#include "output/files_sink.hpp"

#include <algorithm>

namespace cupola {

FilesSink::FilesSink(std::string dir, std::vector<std::string> formats)
    : formats_(formats), writer_(std::move(dir), std::move(formats)) {}

bool FilesSink::wants(const std::string& format) const {
    return std::find(formats_.begin(), formats_.end(), format) != formats_.end();
}

void FilesSink::take(const ProjectorFrame& frame) {
    if (!frame.warped()) {
        last_wait_ms_ = writer_.submit(frame.read_channel(), frame.meta(), frame.exposure());
        return;
    }
    Image linear = wants("exr") ? frame.read_linear() : Image{};
    EncodedImage encoded = wants("png") ? frame.read_encoded() : EncodedImage{};
    last_wait_ms_ = writer_.submit_projected(std::move(linear), std::move(encoded), frame.meta(), frame.exposure());
}

uint64_t FilesSink::finish() {
    writer_.flush();
    return writer_.failed();
}

}  // namespace cupola
