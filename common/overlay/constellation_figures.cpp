#include "overlay/constellation_figures.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace cupola {

namespace {

using nlohmann::json;

// Errors name the source and the path to the field.
struct Place {
    const std::string& source;
    std::string path;
    Place at(const std::string& key) const { return {source, path.empty() ? key : path + "." + key}; }
    Place at(size_t i) const { return {source, path + "[" + std::to_string(i) + "]"}; }
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error(source + ": " + (path.empty() ? "" : path + ": ") + what);
    }
};

const json& member(const json& o, const std::string& key, const Place& p) {
    if (!o.is_object()) p.fail("is not an object");
    const auto it = o.find(key);
    if (it == o.end()) p.fail("has no \"" + key + "\"");
    return *it;
}

double number(const json& v, const Place& p) {
    if (!v.is_number()) p.fail("is not a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) p.fail("is not finite");
    return x;
}

std::string text(const json& v, const Place& p) {
    if (!v.is_string()) p.fail("is not a string");
    return v.get<std::string>();
}

const json& array(const json& v, const Place& p, size_t min_size) {
    if (!v.is_array()) p.fail("is not an array");
    if (v.size() < min_size)
        p.fail("has " + std::to_string(v.size()) + " entries, at least " + std::to_string(min_size) + " needed");
    return v;
}

glm::dvec3 point(const json& v, const Place& p) {
    array(v, p, 2);
    if (v.size() != 2) p.fail("is not a [right ascension, declination] pair");
    const double ra = number(v[0], p.at(0)), dec = number(v[1], p.at(1));
    if (ra < 0.0 || ra >= 360.0) p.at(0).fail("right ascension " + std::to_string(ra) + " is outside [0, 360)");
    if (dec < -90.0 || dec > 90.0) p.at(1).fail("declination " + std::to_string(dec) + " is outside [-90, 90]");
    return radec_deg_to_dir(ra, dec);
}

std::vector<std::vector<glm::dvec3>> polylines(const json& v, const Place& p, size_t min_points) {
    std::vector<std::vector<glm::dvec3>> out;
    array(v, p, 0);
    for (size_t i = 0; i < v.size(); ++i) {
        const Place pi = p.at(i);
        const json& line = array(v[i], pi, min_points);
        std::vector<glm::dvec3> pts;
        for (size_t k = 0; k < line.size(); ++k) pts.push_back(point(line[k], pi.at(k)));
        out.push_back(std::move(pts));
    }
    return out;
}

ConstellationFigure figure(const json& c, const Place& p) {
    ConstellationFigure f;
    f.id = text(member(c, "id", p), p.at("id"));
    f.name = text(member(c, "name", p), p.at("name"));
    const double rank = number(member(c, "rank", p), p.at("rank"));
    if (rank != 1.0 && rank != 2.0 && rank != 3.0) p.at("rank").fail("is not 1, 2 or 3");
    f.rank = static_cast<int>(rank);
    const Place pl = p.at("labels");
    const json& labels = array(member(c, "labels", p), pl, 1);
    for (size_t i = 0; i < labels.size(); ++i) {
        const Place li = pl.at(i);
        const json& l = labels[i];
        f.labels.push_back({text(member(l, "text", li), li.at("text")),
                            point(json::array({member(l, "ra_deg", li), member(l, "dec_deg", li)}), li)});
    }
    f.lines = polylines(member(c, "lines", p), p.at("lines"), 2);
    return f;
}

}  // namespace

glm::dvec3 radec_deg_to_dir(double ra_deg, double dec_deg) {
    const double ra = glm::radians(ra_deg), dec = glm::radians(dec_deg);
    return {std::cos(dec) * std::cos(ra), std::cos(dec) * std::sin(ra), std::sin(dec)};
}

std::vector<ConstellationFigure> parse_constellation_figures(const std::string& doc_text, const std::string& source) {
    const Place root{source, ""};
    json doc;
    try {
        doc = json::parse(doc_text);
    } catch (const json::exception& e) {  // a syntax error, or a number out of range (406)
        root.fail(std::string("is not JSON: ") + e.what());
    }
    const Place pc = root.at("constellations");
    const json& cs = array(member(doc, "constellations", root), pc, 1);
    std::vector<ConstellationFigure> out;
    for (size_t i = 0; i < cs.size(); ++i) out.push_back(figure(cs[i], pc.at(i)));
    const Place pb = root.at("boundaries");
    const json& bs = array(member(doc, "boundaries", root), pb, 0);
    for (size_t i = 0; i < bs.size(); ++i) {
        const Place bi = pb.at(i);
        const std::string id = text(member(bs[i], "id", bi), bi.at("id"));
        ConstellationFigure* owner = nullptr;
        for (auto& f : out)
            if (f.id == id) owner = &f;
        if (!owner) bi.at("id").fail("\"" + id + "\" is not one of the constellations");
        for (auto& ring : polylines(member(bs[i], "polygons", bi), bi.at("polygons"), 3))
            owner->boundaries.push_back(std::move(ring));
    }
    return out;
}

std::vector<ConstellationFigure> load_constellation_figures(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error(file + ": cannot be opened");
    std::ostringstream s;
    s << in.rdbuf();
    return parse_constellation_figures(s.str(), file);
}

}  // namespace cupola
