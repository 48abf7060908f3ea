// grade_reporter.cpp: the doctest reporter behind the assignment kits' `grade` command.
//
// Every test executable of the project (and of every assignment kit) links this file, so
// any of them can be run as
//
//     test_ch02 --reporters=grade            (add --out=grade.txt to write a file)
//
// Points are declared next to the test, in its description, never in a separate list:
//
//     TEST_CASE("name" * doctest::description("points: 2; exercise: ch02-edge-bias"))
//
// Output, one line per test case in the order doctest runs them (by file, then line),
// then one total line; nothing else, no timings, no colours, so that a course can collect
// it:
//
//     PASS 2/2 ch02-edge-bias the top-left rule covers shared edges once
//     FAIL 0/3 ch02-block-walk 8x8 blocks visit the same pixels as the box walk
//     PASS 0/0 - edge functions are exact in fixed point
//     SKIP 0/1 - a test that was filtered out or marked doctest::skip
//     TOTAL 2/5 points; 2/3 test cases passed
//
// Fields are separated by single spaces: STATUS EARNED/DECLARED EXERCISE NAME, where
// EXERCISE is "-" for a test that checks no exercise and NAME runs to the end of the
// line. A test case earns all of its points when it passes (every subcase included) and
// none otherwise. A skipped test case counts in neither number of the TOTAL line.
//
// Below a FAIL line come the reasons, each on a line of its own that starts with two
// spaces: the first failed checks (file name, line, expression and values), an exception
// the test case threw, a crash doctest caught. `--list-test-cases --reporters=grade`
// prints "TEST RUN|SKIP POINTS EXERCISE VISIBILITY NAME" per test case (SKIP: marked
// doctest::skip), in the order of a run; the kits' grade runner
// (src/kits/template/grade_runner.cpp) reads it to run every test case in a process of
// its own. VISIBILITY is Gradescope's: the description's "visibility: V", else
// "after_published" for a test case in a folder named hidden (the teacher's hidden tests,
// tests/hidden/, which only the autograder holds), else "visible".
//
// Run by the grade runner, the reporter writes nowhere a file name says: the runner sets
// EXACTPIXELS_GRADE_CHANNEL=K,R, the reporter reads a random key from descriptor K
// (before any test runs), closes it, and writes every line, prefixed by the key and a
// space, to descriptor R. The runner ignores lines without the key, so code under test
// that prints "PASS" or rewrites a file cannot speak for the reporter.
#include "support/declared_points.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <ostream>
#include <sstream>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

namespace exactpixels::testing {

namespace {

/// What a test case's description declares (declared_points.hpp), with "-" for no
/// exercise as the grade lines print it.
struct Declared {
    int points = 0;                     ///< points earned when the test case passes
    std::string exercise = "-";         ///< the exercise region it checks, "-" for none
    std::string visibility = "visible"; ///< see the top of the file
};

Declared parse_description(const doctest::TestCaseData& test) {
    Declared declared;
    const std::string_view file = test.m_file.c_str();
    if (file.find("/hidden/") != std::string_view::npos ||
        file.find("\\hidden\\") != std::string_view::npos) {
        declared.visibility = "after_published";
    }
    if (test.m_description == nullptr) {
        return declared;
    }
    const DeclaredPoints d = parse_declared_points(test.m_description);
    declared.points = d.points;
    declared.exercise = d.exercise.empty() ? "-" : d.exercise;
    if (!d.visibility.empty()) {
        declared.visibility = d.visibility;
    }
    return declared;
}

/// An output stream buffer that writes to a file descriptor (the grade runner's pipe).
/// Not /dev/fd/N: a test program the grader runs as another user, and cannot read, may
/// not open its own /proc/self/fd.
class DescriptorBuffer : public std::streambuf {
  public:
    explicit DescriptorBuffer(int fd) : fd_(fd) {}
    ~DescriptorBuffer() override {
        sync();
        ::close(fd_);
    }

  protected:
    int overflow(int c) override {
        if (c != traits_type::eof()) {
            pending_.push_back(static_cast<char>(c));
        }
        return traits_type::not_eof(c);
    }
    std::streamsize xsputn(const char* text, std::streamsize n) override {
        pending_.append(text, static_cast<std::size_t>(n));
        return n;
    }
    int sync() override {
        std::size_t done = 0;
        while (done < pending_.size()) {
            const ssize_t n =
                ::write(fd_, pending_.data() + done, pending_.size() - done);
            if (n <= 0) {
                return -1;
            }
            done += static_cast<std::size_t>(n);
        }
        pending_.clear();
        return 0;
    }

  private:
    int fd_;
    std::string pending_;
};

/// Prints one line per test case and a total; see the top of this file.
class GradeReporter : public doctest::IReporter {
  public:
    explicit GradeReporter(const doctest::ContextOptions& options) : out_(*options.cout) {
        open_channel();
    }

    void report_query(const doctest::QueryData& query) override {
        // With --list-test-cases: every test case with its declared points.
        for (unsigned i = 0; i < query.num_data; ++i) {
            const Declared d = parse_description(*query.data[i]);
            out() << prefix_ << "TEST " << (query.data[i]->m_skip ? "SKIP " : "RUN ")
                  << d.points << ' ' << d.exercise << ' ' << d.visibility << ' '
                  << query.data[i]->m_name << '\n';
        }
    }

    void test_run_start() override {}

    void test_run_end(const doctest::TestRunStats&) override {
        out() << prefix_ << "TOTAL " << earned_ << '/' << declared_ << " points; "
              << passed_ << '/' << cases_ << " test cases passed" << std::endl;
    }

    void test_case_start(const doctest::TestCaseData& test) override {
        current_ = &test;
        reasons_.clear();
        failed_checks_ = 0;
    }
    void test_case_reenter(const doctest::TestCaseData&) override {}

    void test_case_end(const doctest::CurrentTestCaseStats& stats) override {
        line(stats.testCaseSuccess ? "PASS" : "FAIL", *current_, stats.testCaseSuccess);
    }

    void test_case_exception(const doctest::TestCaseException& exception) override {
        reasons_.push_back(std::string(exception.is_crash ? "crashed: " : "threw: ") +
                           one_line(exception.error_string.c_str()));
    }

    void subcase_start(const doctest::SubcaseSignature&) override {}
    void subcase_end() override {}

    void log_assert(const doctest::AssertData& data) override {
        if (!data.m_failed) {
            return;
        }
        if (++failed_checks_ > max_reasons) {
            return;
        }
        std::ostringstream reason;
        reason << base_name(data.m_file) << ':' << data.m_line << ": "
               << doctest::assertString(data.m_at) << "( " << data.m_expr << " )";
        if (data.m_threw) {
            reason << " threw: " << data.m_exception.c_str();
        } else if (data.m_decomp.size() > 0) {
            reason << " is false; values: " << data.m_decomp.c_str();
        }
        reasons_.push_back(one_line(reason.str()));
    }

    void log_message(const doctest::MessageData&) override {}

    void test_case_skipped(const doctest::TestCaseData& test) override {
        line("SKIP", test, false);
    }

  private:
    void line(const char* status, const doctest::TestCaseData& test, bool passed) {
        const Declared d = parse_description(test);
        const int earned = passed ? d.points : 0;
        if (status[0] != 'S') { // a skipped test case counts in neither total
            earned_ += earned;
            declared_ += d.points;
            passed_ += passed ? 1 : 0;
            ++cases_;
        }
        // Flushed per line, so that a crash later in the run keeps the lines before it.
        out() << prefix_ << status << ' ' << earned << '/' << d.points << ' '
              << d.exercise << ' ' << test.m_name << '\n';
        if (!passed && status[0] != 'S') {
            for (const auto& reason : reasons_) {
                out() << prefix_ << "  " << reason << '\n';
            }
            if (failed_checks_ > max_reasons) {
                out() << prefix_ << "  ... and " << failed_checks_ - max_reasons
                      << " more failed checks\n";
            }
        }
        out().flush();
    }

    /// The grade runner's channel (see the top of the file), when it set one.
    void open_channel() {
        const char* fds = std::getenv("EXACTPIXELS_GRADE_CHANNEL");
        int key_fd = -1, report_fd = -1;
        if (fds == nullptr || std::sscanf(fds, "%d,%d", &key_fd, &report_fd) != 2) {
            return;
        }
        ::unsetenv("EXACTPIXELS_GRADE_CHANNEL");
        // The runner writes the key and closes its end: read to the end of the pipe.
        std::string text;
        char buffer[64];
        for (ssize_t n = 0; text.size() < sizeof buffer &&
                            (n = ::read(key_fd, buffer, sizeof buffer)) > 0;) {
            text.append(buffer, static_cast<std::size_t>(n));
        }
        ::close(key_fd);
        while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) {
            text.pop_back();
        }
        prefix_ = text + ' ';
        buffer_ = std::make_unique<DescriptorBuffer>(report_fd);
        channel_ = std::make_unique<std::ostream>(buffer_.get());
    }

    std::ostream& out() { return channel_ ? *channel_ : out_; }

    /// "/any/where/tests/ch02_x.cpp" -> "ch02_x.cpp": no machine's paths in a grade.
    static std::string base_name(const char* file) {
        const std::string_view path = file == nullptr ? "" : file;
        const auto slash = path.find_last_of("/\\");
        return std::string(slash == std::string_view::npos ? path
                                                           : path.substr(slash + 1));
    }

    /// Line breaks and tabs become spaces and long text is cut, so a reason stays a line.
    static std::string one_line(std::string text) {
        for (char& c : text) {
            if (c == '\n' || c == '\r' || c == '\t') {
                c = ' ';
            }
        }
        if (text.size() > max_reason_chars) {
            text = text.substr(0, max_reason_chars) + "...";
        }
        return text;
    }

    /// At most this many failed checks are listed per test case.
    static constexpr int max_reasons = 5;
    /// A reason line is cut after this many characters.
    static constexpr std::size_t max_reason_chars = 300;

    std::ostream& out_;
    std::unique_ptr<DescriptorBuffer> buffer_; // the grade runner's pipe, if any
    std::unique_ptr<std::ostream> channel_;    // writing into it
    std::string prefix_;                       // its key and a space, or nothing
    const doctest::TestCaseData* current_ = nullptr;
    std::vector<std::string> reasons_; // why the current test case fails
    int failed_checks_ = 0;
    int earned_ = 0, declared_ = 0, passed_ = 0, cases_ = 0;
};

} // namespace

REGISTER_REPORTER("grade", 1, GradeReporter);

} // namespace exactpixels::testing
