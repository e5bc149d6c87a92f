#include "test_util.h"

#include "gi/gl/debug.h"

#include <array>
#include <cstdio>
#include <memory>

namespace gi::test {

EGLContextHeadless& context() {
    static EGLContextHeadless ctx;
    return ctx;
}

std::filesystem::path tempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (auto& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    auto dir = std::filesystem::temp_directory_path() / "gi_tests" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

CommandResult runCommand(const std::string& command) {
    CommandResult r;
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((command + " 2>&1").c_str(), "r"), pclose);
    if (!pipe) return r;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), pipe.get())) > 0) r.output.append(buf.data(), n);
    int status = pclose(pipe.release());
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

void GLTest::SetUp() {
    context();
    mErrorsBefore = gl::debugErrorCount();
}

void GLTest::TearDown() { EXPECT_EQ(gl::debugErrorCount(), mErrorsBefore) << "GL debug output reported errors"; }

}  // namespace gi::test
