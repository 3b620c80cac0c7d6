// atomic_file.cpp: temporary file + fsync + rename (see atomic_file.hpp).
#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace idk::core {

namespace {

std::runtime_error ioError(const std::filesystem::path& path, const std::string& what) {
    return std::runtime_error(path.string() + ": " + what + ": " + std::strerror(errno));
}

// fsync so the rename never publishes a name whose data is still only in the page cache (after a power loss the
// file would be empty on ext4 with delayed allocation).
void syncFile(const std::filesystem::path& path, bool directory) {
    const int fd = ::open(path.c_str(), (directory ? O_DIRECTORY : 0) | O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw ioError(path, "cannot open to flush");
    const int synced = ::fsync(fd);
    const int savedErrno = errno;
    ::close(fd);
    errno = savedErrno;
    if (synced != 0 && !directory) throw ioError(path, "cannot flush to disk");
}

}  // namespace

void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& temporary)>& write) {
    std::filesystem::path folder = path.parent_path();
    if (folder.empty()) folder = ".";
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw std::runtime_error(path.string() + ": is a directory");

    const std::string extension = path.extension().string();
    std::string name = (folder / ("." + path.stem().string() + ".partial-XXXXXX" + extension)).string();
    std::vector<char> buffer(name.begin(), name.end());
    buffer.push_back('\0');
    // mkstemps creates the file with O_EXCL: a name an attacker prepared (e.g. a symlink) is never followed.
    const int fd = ::mkstemps(buffer.data(), int(extension.size()));
    if (fd < 0) throw ioError(path, "cannot create a temporary file in " + folder.string());
    // mkstemps makes the file 0600; a finished output gets the permissions a plain create would (0666 & ~umask).
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
    ::close(fd);
    const std::filesystem::path temporary(buffer.data());
    try {
        write(temporary);
        syncFile(temporary, false);
        if (::rename(temporary.c_str(), path.c_str()) != 0) throw ioError(path, "cannot move the finished file into place");
    } catch (...) {
        std::filesystem::remove(temporary, ec);
        throw;
    }
    syncFile(folder, true);  // the rename itself; best effort
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        const int fd = ::open(temporary.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
        if (fd < 0) throw ioError(path, "cannot open for writing");
        size_t done = 0;
        while (done < bytes.size()) {
            const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                const int savedErrno = errno;
                ::close(fd);
                errno = savedErrno;
                throw ioError(path, "cannot write");
            }
            done += size_t(n);
        }
        if (::close(fd) != 0) throw ioError(path, "cannot write");
    });
}

}  // namespace idk::core
