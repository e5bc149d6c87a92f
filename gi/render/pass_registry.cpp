#include "gi/render/pass.h"

#include "gi/preset/reflect.h"

namespace gi {

namespace {

template <auto Member>
uint8_t sectionChanges(const FrameSettings& before, const FrameSettings& after) {
    return diff(before.*Member, after.*Member);
}

template <class S, S FrameSections::*Member>
PassInfo entry() {
    PassInfo info{S::kSection, S::kRole, &S::createPass, &S::estimateBytes, nullptr, nullptr, &sectionChanges<Member>};
    if constexpr (requires(const FrameSettings& fs) { S::checkTime(fs); }) info.checkTime = &S::checkTime;
    if constexpr (requires(const FrameSettings& fs) { S::notes(fs); }) info.notes = &S::notes;
    if constexpr (requires { S::kGathersSky; }) info.gathersSky = S::kGathersSky;
    return info;
}

std::vector<PassInfo> makeRegistry() {
    std::vector<PassInfo> out;
#define GI_SECTION_ENTRY(Type, name) \
    if constexpr (PassSettings<Type>) out.push_back(entry<Type, &FrameSections::name>());
    GI_FRAME_SECTIONS(GI_SECTION_ENTRY)
#undef GI_SECTION_ENTRY
    return out;
}

}  // namespace

const std::vector<PassInfo>& passRegistry() {
    static const std::vector<PassInfo> registry = makeRegistry();
    return registry;
}

const PassInfo* findPass(std::string_view name) {
    for (const PassInfo& p : passRegistry())
        if (p.name == name) return &p;
    return nullptr;
}

bool passActive(const PassInfo& info, const FrameSettings& fs) {
    return info.role == PassRole::Effect || fs.technique == info.name;
}

std::vector<std::string> TechniqueChoice::choices() {
    std::vector<std::string> names{std::string(kNone)};
    for (const PassInfo& p : passRegistry())
        if (p.role == PassRole::Technique) names.emplace_back(p.name);
    return names;
}

}  // namespace gi
