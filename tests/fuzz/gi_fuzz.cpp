// gi-fuzz: a deterministic, structure-aware fuzzer of the glTF loader and the preset parser,
// run in-process (tests/fuzz/mutator.h says what it mutates). Every iteration draws its own
// generator from (seed, iteration), so any one can be replayed alone with --only and printed as
// a regression case for tests/fuzz/regressions.json.
//
// An input passes when it loads or fails with gi::Error (one line naming the file). It fails the
// run when anything else escapes (std::bad_alloc, std::length_error), when it takes longer than
// --timeout-s (a hang), or when a sanitizer stops the process (a crash; the replay line is printed
// first). With --render-every K, every K-th scene that loads is also rendered at 32x32 on the
// EGL context, as gi-render would, so stalls in the GPU passes are caught too.
//
//   gi-fuzz --seconds 120 --seed 1          what CI runs (scripts/quickstart.sh test, sanitizer build)
//   gi-fuzz --seed 1 --only 4711 --print    the edits of one iteration, and its outcome
//   gi-fuzz --case class3-image-view-offset-wraps --write x.glb
//                                           a regression case (or with --only, an iteration) as a
//                                           file, to open in gi-render or the editor
#include "mutator.h"

#include "gi/gl/debug.h"
#include "gi/platform/egl_context.h"
#include "gi/preset/preset.h"
#include "gi/render/renderer.h"
#include "gi/scene/scene.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sys/resource.h>
#include <unistd.h>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GI_FUZZ_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define GI_FUZZ_ASAN 1
#endif
#ifdef GI_FUZZ_ASAN
#include <sanitizer/common_interface_defs.h>
#endif

namespace {

using namespace gi;
using namespace gi::fuzz;
namespace fs = std::filesystem;

// What a signal handler or the sanitizer's death callback prints: the replay command.
char gReplay[256] = "gi-fuzz: failed before the first iteration\n";

void printReplay() {
    ssize_t ignored = write(STDERR_FILENO, gReplay, std::strlen(gReplay));
    (void)ignored;
}

void onAlarm(int) {
    const char* hang = "gi-fuzz: HANG: an input ran past --timeout-s\n";
    ssize_t ignored = write(STDERR_FILENO, hang, std::strlen(hang));
    (void)ignored;
    printReplay();
    _exit(3);
}

#ifndef GI_FUZZ_ASAN
// Without a sanitizer's death callback, fatal signals print the replay line themselves.
void onFatalSignal(int sig) {
    printReplay();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}
#endif

struct Outcome {
    bool loaded = false;
    std::string error;  // gi::Error's message when refused
};

// The refusal's kind, for the summary: its text with the file name and numbers taken out.
std::string kindOf(const std::string& message) {
    std::string s = message;
    if (auto colon = s.find(": "); colon != std::string::npos) s = s.substr(colon + 2);
    std::string out;
    for (char c : s) {
        if (std::isdigit(static_cast<unsigned char>(c))) {
            if (out.empty() || out.back() != '#') out += '#';
        } else {
            out += c;
        }
        if (out.size() >= 60) break;
    }
    return out;
}

class Fuzzer {
public:
    uint64_t seed = 1;
    double budgetMB = 256.0;
    int renderEvery = 0;
    fs::path corpus, presets;
    bool print = false;
    std::string writeTo;  // with --only or --case: the input is written here

    void init() {
        mSeeds = readSeeds(corpus);
        if (mSeeds.empty()) throw Error(corpus.string() + ": no .glb seeds");
        if (!presets.empty() && fs::is_directory(presets))
            for (const auto& e : fs::directory_iterator(presets))
                if (e.path().extension() == ".json") mPresets.push_back(readTextFile(e.path()));
        std::sort(mPresets.begin(), mPresets.end());
        for (const auto& s : listSettings()) mKeys.push_back(s.key);
        if (renderEvery > 0) {
            mContext = std::make_unique<EGLContextHeadless>();
            mRenderer = std::make_unique<Renderer>();
        }
    }

    // Runs iteration `i`. Returns false when something other than gi::Error escaped.
    bool run(uint64_t i) {
        std::snprintf(gReplay, sizeof gReplay, "gi-fuzz: replay with: gi-fuzz --seed %llu --only %llu --print\n",
                      static_cast<unsigned long long>(seed), static_cast<unsigned long long>(i));
        std::mt19937_64 rng = iterationRng(seed, i);
        bool preset = !mPresets.empty() && rng() % 5 == 0;
        try {
            Outcome o = preset ? runPreset(rng) : runGLTF(rng);
            (o.loaded ? mLoaded : mRefused)++;
            if (!o.loaded) mKinds[kindOf(o.error)]++;
            if (print) std::printf("outcome: %s\n", o.loaded ? "loaded" : o.error.c_str());
            return true;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "gi-fuzz: FAILURE: %s escaped: %s\n", typeid(e).name(), e.what());
            printReplay();
            return false;
        }
    }

    void summary(double seconds, uint64_t tries) const {
        struct rusage ru {};
        getrusage(RUSAGE_SELF, &ru);
        std::printf("gi-fuzz: %llu tries in %.0f s (%.1f/s), %llu loaded, %llu refused with gi::Error, %llu rendered, "
                    "peak RSS %.0f MiB, budget %.0f MiB\n",
                    static_cast<unsigned long long>(tries), seconds, double(tries) / std::max(seconds, 1e-9),
                    static_cast<unsigned long long>(mLoaded), static_cast<unsigned long long>(mRefused),
                    static_cast<unsigned long long>(mRendered), double(ru.ru_maxrss) / 1024.0, budgetMB);
        std::vector<std::pair<uint64_t, std::string>> kinds;
        for (const auto& [k, n] : mKinds) kinds.push_back({n, k});
        std::sort(kinds.rbegin(), kinds.rend());
        std::printf("gi-fuzz: %zu kinds of refusal; the most common:\n", kinds.size());
        for (size_t k = 0; k < std::min<size_t>(kinds.size(), 25); ++k)
            std::printf("  %8llu  %s\n", static_cast<unsigned long long>(kinds[k].first), kinds[k].second.c_str());
    }

private:
    std::vector<GLTFSeed> mSeeds;
    std::vector<std::string> mPresets;
    std::vector<std::string> mKeys;
    std::unique_ptr<EGLContextHeadless> mContext;
    std::unique_ptr<Renderer> mRenderer;
    uint64_t mLoaded = 0, mRefused = 0, mRendered = 0;
    std::map<std::string, uint64_t> mKinds;

    Outcome runGLTF(std::mt19937_64& rng) {
        const GLTFSeed& s = mSeeds[rng() % mSeeds.size()];
        json edits = randomEdits(s, rng);
        if (print) std::printf("seed: %s\nedits: %s\n", s.name.c_str(), edits.dump().c_str());
        FuzzInput in = applyEdits(s, edits);
        if (!writeTo.empty()) write(in);
        Outcome o;
        try {
            Scene scene = loadGLTFFromMemory(in.bytes, in.binary, in.binary ? "fuzz.glb" : "fuzz.gltf", corpus, budgetMB);
            o.loaded = true;
            if (renderEvery > 0 && (mLoaded % uint64_t(renderEvery)) == 0) render(scene);
        } catch (const Error& e) {
            o.error = e.what();
            if (o.error.find('\n') != std::string::npos) throw std::runtime_error("a gi::Error of more than one line: " + o.error);
        }
        return o;
    }

    void write(const FuzzInput& in) const {
        std::ofstream out(writeTo, std::ios::binary);
        out.write(reinterpret_cast<const char*>(in.bytes.data()), std::streamsize(in.bytes.size()));
        if (!out) throw Error(writeTo + ": cannot write");
    }

public:
    // Writes regression case `name` (tests/fuzz/regressions.json) to --write.
    void writeCase(const std::string& name) {
        json cases = json::parse(readTextFile(corpus.parent_path() / "regressions.json"))["cases"];
        for (const json& c : cases)
            if (c["name"] == name) {
                write(applyEdits(readSeed(corpus / c["seed"].get<std::string>()), c["edits"]));
                std::printf("%s: expected: %s\n", name.c_str(), c["expect"].get<std::string>().c_str());
                return;
            }
        throw Error("no regression case '" + name + "' in " + (corpus.parent_path() / "regressions.json").string());
    }

private:
    void render(Scene& scene) {
        if (scene.cameras.empty()) scene.cameras.push_back(frameBounds(scene.bounds));
        Preset p;
        p.camera.sceneCamera = 0;
        p.lightsFromScene = true;
        p.render.shadowMapSize = 128;
        p.render.memoryBudgetMB = float(budgetMB);
        FrameSettings frame = frameSettings(p, scene, 32, 32);
        Renderer::checkBudget(frame, scene);
        mRenderer->setScene(scene);
        mRenderer->render(frame);
        (void)mRenderer->readLDR();
        if (gl::debugErrorCount() > 0) throw std::runtime_error("OpenGL reported errors while rendering a fuzzed scene");
        ++mRendered;
    }

    Outcome runPreset(std::mt19937_64& rng) {
        const std::string& base = mPresets[rng() % mPresets.size()];
        std::string text = mutatePreset(base, rng);
        std::string assignment;
        if (rng() % 3 == 0) {
            static const std::vector<std::string> values = {"-1", "0", "4096", "1e300", "nan", "inf", "", "x", "[1,2]", "true",
                                                            "18446744073709551615", "-2147483649", "0.5", "1e999", "-1e999"};
            assignment = mKeys[rng() % mKeys.size()] + "=" + values[rng() % values.size()];
        }
        if (print) std::printf("preset: %s\nset: %s\n", text.c_str(), assignment.c_str());
        Outcome o;
        try {
            Preset p = presetFromText(text, "fuzz.json");
            if (!assignment.empty()) applySetting(p, assignment);
            if (isBuiltinScene(p.header.scene)) {
                Scene scene = makeBuiltinScene(p.header.scene);
                FrameSettings frame = frameSettings(p, scene, 64, 64);
                Renderer::checkBudget(frame, scene);
            }
            o.loaded = true;
        } catch (const Error& e) {
            o.error = e.what();
            if (o.error.find('\n') != std::string::npos) throw std::runtime_error("a gi::Error of more than one line: " + o.error);
        }
        return o;
    }
};

int run(int argc, char** argv) {
    CLI::App app{"gi-fuzz: structure-aware fuzzing of the glTF loader and the preset parser"};
    Fuzzer f;
    double seconds = 60.0, timeout = 60.0;
    uint64_t iterations = 0, start = 0;
    int64_t only = -1;
    f.corpus = fs::path(GI_SOURCE_DIR) / "tests" / "fuzz" / "corpus";
    f.presets = fs::path(GI_SOURCE_DIR) / "presets";
    app.add_option("--seed", f.seed, "Seed of the run (iterations draw from seed and their index)");
    app.add_option("--seconds", seconds, "Stop after this long");
    app.add_option("--iterations", iterations, "Stop after this many tries (0: no limit)");
    app.add_option("--start", start, "First iteration index");
    app.add_option("--only", only, "Run iteration N alone");
    app.add_flag("--print", f.print, "Print each input's edits and outcome");
    app.add_option("--corpus", f.corpus, "Folder of .glb seeds");
    app.add_option("--presets", f.presets, "Folder of preset seeds ('' for none)");
    app.add_option("--budget-mb", f.budgetMB, "render.memoryBudgetMB for the loads");
    app.add_option("--render-every", f.renderEvery, "Also render every K-th scene that loads (0: never)");
    app.add_option("--timeout-s", timeout, "An input taking longer is a hang");
    std::string caseName;
    app.add_option("--case", caseName, "Write this regression case (tests/fuzz/regressions.json) to --write and exit");
    app.add_option("--write", f.writeTo, "With --only or --case: write the input to this file");
    CLI11_PARSE(app, argc, argv);
    if (!caseName.empty()) {
        if (f.writeTo.empty()) throw Error("--case needs --write FILE");
        f.writeCase(caseName);
        return 0;
    }

    std::signal(SIGALRM, onAlarm);
#ifdef GI_FUZZ_ASAN
    __sanitizer_set_death_callback(printReplay);
#else
    for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, onFatalSignal);
#endif
    f.init();
    auto t0 = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    uint64_t tries = 0;
    double lastReport = 0.0;
    bool ok = true;
    for (uint64_t i = only >= 0 ? uint64_t(only) : start;; ++i) {
        alarm(unsigned(std::max(1.0, timeout)));
        ok = f.run(i) && ok;
        alarm(0);
        ++tries;
        if (!ok || only >= 0) break;
        if (iterations && tries >= iterations) break;
        double t = elapsed();
        if (t >= seconds) break;
        if (t - lastReport >= 10.0) {
            lastReport = t;
            std::fprintf(stderr, "gi-fuzz: %llu tries, %.0f s\n", static_cast<unsigned long long>(tries), t);
        }
    }
    f.summary(elapsed(), tries);
    std::snprintf(gReplay, sizeof gReplay, "gi-fuzz: the run ended; a report after this is about the whole run (a leak at exit)\n");
    return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) { return gi::reportErrors("gi-fuzz", [&] { return run(argc, argv); }); }
