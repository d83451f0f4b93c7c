#include "libcommon/data_file.h"

#include <unistd.h>

namespace rs {

std::string ResolveDataFile(const std::string& name, const std::string& sceneFile) {
    if (name.empty() || name[0] == '/' || access(name.c_str(), F_OK) == 0) return name;
    const std::string::size_type slash = sceneFile.find_last_of('/');
    if (slash == std::string::npos) return name;  // the scene's directory is the working one
    std::string beside = sceneFile.substr(0, slash + 1) + name;
    return access(beside.c_str(), F_OK) == 0 ? beside : name;
}

}  // namespace rs
