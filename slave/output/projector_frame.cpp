#include "output/projector_frame.hpp"

#include <stdexcept>

namespace cupola {

const WarpPass& ProjectorFrame::warp() const {
    if (!warp_) throw std::logic_error("projector frame: the warp pass did not run for this frame");
    return *warp_;
}

Image ProjectorFrame::read_linear() const {
    ++read_backs_;
    return warp().read_linear();
}

EncodedImage ProjectorFrame::read_encoded() const {
    ++read_backs_;
    EncodedImage img;
    img.width = warp().width();
    img.height = warp().height();
    img.rgba = warp().read_encoded();
    return img;
}

}  // namespace cupola
