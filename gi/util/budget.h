// Memory that input can make huge (a scene's accessors and images, an environment map) is
// counted here before it is allocated, against render.memoryBudgetMB.
#pragma once

#include "gi/util/error.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace gi {

// render.memoryBudgetMB's default, for loaders called without settings.
constexpr double kDefaultMemoryBudgetMB = 2048.0;

class MemoryBudget {
public:
    explicit MemoryBudget(double budgetMB = kDefaultMemoryBudgetMB) : mLimit(budgetMB * 1024.0 * 1024.0) {}

    // Counts `bytes` (a double, so products of hostile counts cannot wrap) for `what`; throws
    // gi::Error naming the setting when the total would pass the budget.
    void reserve(double bytes, const std::string& what) {
        if (!(bytes >= 0.0) || mUsed + bytes > mLimit) {
            char buf[96];
            std::snprintf(buf, sizeof buf, " needs %.0f MiB, past the budget of %.0f MiB (key 'render.memoryBudgetMB')",
                          bytes / (1024.0 * 1024.0), mLimit / (1024.0 * 1024.0));
            throw Error(what + buf);
        }
        mUsed += bytes;
    }
    double usedBytes() const { return mUsed; }
    double limitBytes() const { return mLimit; }

private:
    double mLimit;
    double mUsed = 0.0;
};

// Work estimated at `seconds` past render.timeBudgetSeconds is refused with one line naming the
// key, the work, the estimate (`detail`: what it depends on) and what to lower (`remedy`).
inline void checkTimeBudget(double seconds, double budgetSeconds, const std::string& work, const std::string& detail,
                            const std::string& remedy) {
    if (seconds <= budgetSeconds) return;
    char buf[96];
    std::snprintf(buf, sizeof buf, " estimated at %.0f s (", std::ceil(seconds));
    std::string message = "key 'render.timeBudgetSeconds': " + work + buf + detail;
    std::snprintf(buf, sizeof buf, ") exceeds the budget of %.0f s; ", budgetSeconds);
    throw Error(message + buf + remedy + ", or raise render.timeBudgetSeconds");
}

}  // namespace gi
