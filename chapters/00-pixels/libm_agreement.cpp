// The C library's mathematical functions that the library calls (pow, sin, cos, tan, acos,
// log2, hypot, exp) are not correctly rounded, so two C libraries may return different
// doubles for the same argument. This program evaluates each on the same pseudo-random
// arguments, drawn from the ranges the library uses them on, and writes the results' bits;
// run on two machines (or one under an emulator), its `compare` mode counts the results
// that differ and by how many units in the last place. libm_results.sh runs it for
// chapters/00-pixels/libm_results.md.
//   libm_agreement write FILE          evaluate, write the doubles to FILE
//   libm_agreement compare FILE FILE   one Markdown table row per function
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

constexpr int count = 1000000;

struct Function {
    const char* name;  // the table row's name
    const char* where; // what the library uses it for, and on which arguments
};

constexpr Function functions[] = {
    {"pow_decode", "sRGB decoding, pow(s, 2.4), s in [0, 1)"},
    {"pow_encode", "sRGB encoding, pow(l, 1/2.4), l in [0, 1)"},
    {"pow_shine", "specular highlight, pow(c, n), c in [0, 1), n in [1, 200)"},
    {"sin", "rotations, sin(a), a in [-7, 7)"},
    {"cos", "rotations, cos(a), a in [-7, 7)"},
    {"tan", "field of view, tan(a), a in [-1.75, 1.75)"},
    {"acos", "polygon turning, acos(m), m in [-1, 1)"},
    {"log2", "mipmap level, log2(r), r in [0.001, 10000)"},
    {"hypot", "footprint sides, hypot(x, y), x and y in [-1000, 1000)"},
    {"exp", "EWA weights, exp(-d), d in [0, 10)"},
};
constexpr int function_count = sizeof functions / sizeof functions[0];

// splitmix64, then the top 53 bits as a double in [0, 1): the same arguments on every
// machine, with no library distribution in between.
struct Arguments {
    std::uint64_t state = 0x5eed'1234'abcd'0001;
    double unit() {
        std::uint64_t z = (state += 0x9e37'79b9'7f4a'7c15);
        z = (z ^ (z >> 30)) * 0xbf58'476d'1ce4'e5b9;
        z = (z ^ (z >> 27)) * 0x94d0'49bb'1331'11eb;
        z ^= z >> 31;
        return static_cast<double>(z >> 11) * 0x1p-53;
    }
    double in(double low, double high) { return low + (high - low) * unit(); }
};

int write(const char* path) {
    std::vector<double> out;
    out.reserve(static_cast<std::size_t>(count) * function_count);
    Arguments a;
    for (int i = 0; i < count; ++i) {
        out.push_back(std::pow(a.unit(), 2.4));
        out.push_back(std::pow(a.unit(), 1.0 / 2.4));
        const double c = a.unit();
        out.push_back(std::pow(c, a.in(1.0, 200.0)));
        out.push_back(std::sin(a.in(-7.0, 7.0)));
        out.push_back(std::cos(a.in(-7.0, 7.0)));
        out.push_back(std::tan(a.in(-1.75, 1.75)));
        out.push_back(std::acos(a.in(-1.0, 1.0)));
        out.push_back(std::log2(a.in(0.001, 10000.0)));
        const double x = a.in(-1000.0, 1000.0);
        out.push_back(std::hypot(x, a.in(-1000.0, 1000.0)));
        out.push_back(std::exp(-a.in(0.0, 10.0)));
    }
    std::FILE* f = std::fopen(path, "wb");
    if (f == nullptr || std::fwrite(out.data(), sizeof(double), out.size(), f) != out.size() ||
        std::fclose(f) != 0) {
        std::fprintf(stderr, "libm_agreement: cannot write %s\n", path);
        return 2;
    }
    return 0;
}

std::vector<std::int64_t> read(const char* path) {
    std::vector<std::int64_t> bits(static_cast<std::size_t>(count) * function_count);
    std::FILE* f = std::fopen(path, "rb");
    if (f == nullptr || std::fread(bits.data(), sizeof(double), bits.size(), f) != bits.size()) {
        std::fprintf(stderr, "libm_agreement: cannot read %d results from %s\n",
                     count * function_count, path);
        std::exit(2);
    }
    std::fclose(f);
    return bits;
}

// Every result is finite, so the distance between the bit patterns of two results of one
// sign is their distance in units in the last place.
int compare(const char* first, const char* second) {
    const auto a = read(first), b = read(second);
    for (int k = 0; k < function_count; ++k) {
        long differ = 0;
        std::int64_t worst = 0;
        for (std::size_t i = static_cast<std::size_t>(k); i < a.size(); i += function_count) {
            if (a[i] != b[i]) {
                ++differ;
                worst = std::max(worst, std::abs(a[i] - b[i]));
            }
        }
        std::printf("| %s | %s | %ld | %.3f | %lld |\n", functions[k].name, functions[k].where,
                    differ, 100.0 * static_cast<double>(differ) / count,
                    static_cast<long long>(worst));
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "write" && argc == 3) {
        return write(argv[2]);
    }
    if (mode == "compare" && argc == 4) {
        return compare(argv[2], argv[3]);
    }
    std::fprintf(stderr, "usage: libm_agreement write FILE | compare FILE FILE\n");
    return 2;
}
