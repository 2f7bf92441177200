#include "net/key_file.hpp"

#include <sodium.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>

#include <cctype>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cupola {

AuthKey load_key_file(const std::string& path, bool strict) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open key file");
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && (st.st_mode & S_IRWXO)) {
        char mode[8];
        std::snprintf(mode, sizeof mode, "%03o", static_cast<unsigned>(st.st_mode & 0777));
        const std::string msg = path + ": key file is open to every user of this machine (mode " + mode +
                                "); anyone who can read it can forge cluster packets: chmod 600 " + path;
        if (strict) throw std::runtime_error(msg + " (security.strict_key_permissions is on)");
        spdlog::warn("{}", msg);
    }
    std::stringstream ss;
    ss << in.rdbuf();
    std::string hex;
    for (char c : ss.str())
        if (!std::isspace(static_cast<unsigned char>(c))) hex.push_back(c);
    if (hex.size() != 64)
        throw std::runtime_error(path + ": key file must hold 64 hexadecimal digits (32 bytes), found " +
                                 std::to_string(hex.size()) + " characters");
    AuthKey key{};
    size_t bin_len = 0;
    if (sodium_hex2bin(key.data(), key.size(), hex.c_str(), hex.size(), nullptr, &bin_len, nullptr) != 0 ||
        bin_len != key.size())
        throw std::runtime_error(path + ": key file holds characters that are not hexadecimal digits");
    return key;
}

}  // namespace cupola
