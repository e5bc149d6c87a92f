// FNV-1a, 64 bit, shared by the reference cache's keys and the comparison matrix's cell ids.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>

namespace gi {

// FNV-1a, 64 bit: simple, stable across runs and machines, fast enough for Sponza's 100 MB.
class Hasher {
public:
    void bytes(const void* data, size_t n) {
        const auto* p = static_cast<const uint8_t*>(data);
        for (size_t i = 0; i < n; ++i) {
            mHash ^= p[i];
            mHash *= 0x100000001b3ULL;
        }
    }
    template <class T>
    void value(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes(&v, sizeof(T));
    }
    void text(const std::string& s) {
        value(s.size());
        bytes(s.data(), s.size());
    }
    uint64_t result() const { return mHash; }

private:
    uint64_t mHash = 0xcbf29ce484222325ULL;
};

}  // namespace gi
