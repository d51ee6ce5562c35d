#include "text_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "user_error.h"

namespace bench {

void writeTextFile(const std::string& path, const std::string& content) {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    if (file) file.write(content.data(), std::streamsize(content.size()));
    if (file) file.close();
    if (!file) throw ddt::UserError(path + ": cannot write (" + std::strerror(errno) + ")");
}

}  // namespace bench
