#include "bookcheck_cdp.hpp"

#include "support/text_file.hpp"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <poll.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace exactpixels::bookcheck {

// ---------------------------------------------------------------------------------------
// JSON

const Json& Json::operator[](const std::string& key) const {
    static const Json null_value;
    if (type != Type::object) {
        return null_value;
    }
    const auto found = object.find(key);
    return found == object.end() ? null_value : found->second;
}

bool Json::has(const std::string& key) const {
    return type == Type::object && object.count(key) > 0;
}

const std::string& Json::str() const {
    static const std::string empty;
    return type == Type::string ? string : empty;
}

namespace {

struct Parser {
    const std::string& text;
    std::size_t at = 0;

    [[noreturn]] void fail(const char* what) const {
        throw std::runtime_error("JSON: " + std::string(what) + " at offset " +
                                 std::to_string(at));
    }
    void skip_space() {
        while (at < text.size() && std::strchr(" \t\r\n", text[at]) != nullptr) {
            ++at;
        }
    }
    char peek() {
        skip_space();
        if (at >= text.size()) {
            fail("unexpected end");
        }
        return text[at];
    }
    void expect(char c) {
        if (peek() != c) {
            fail("unexpected character");
        }
        ++at;
    }
    bool literal(const char* word) {
        const std::size_t n = std::strlen(word);
        if (text.compare(at, n, word) == 0) {
            at += n;
            return true;
        }
        return false;
    }
    unsigned hex4() {
        if (at + 4 > text.size()) {
            fail("short \\u escape");
        }
        const unsigned value =
            static_cast<unsigned>(std::stoul(text.substr(at, 4), nullptr, 16));
        at += 4;
        return value;
    }
    std::string parse_string() {
        expect('"');
        std::string out;
        while (true) {
            if (at >= text.size()) {
                fail("unterminated string");
            }
            const char c = text[at++];
            if (c == '"') {
                return out;
            }
            if (c != '\\') {
                out += c;
                continue;
            }
            if (at >= text.size()) {
                fail("unterminated escape");
            }
            const char e = text[at++];
            switch (e) {
            case 'n':
                out += '\n';
                break;
            case 't':
                out += '\t';
                break;
            case 'r':
                out += '\r';
                break;
            case 'b':
                out += '\b';
                break;
            case 'f':
                out += '\f';
                break;
            case 'u': {
                unsigned code = hex4();
                if (code >= 0xD800 && code < 0xDC00 && literal("\\u")) {
                    const unsigned low = hex4();
                    code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
                }
                exactpixels::testing::append_utf8(out, code);
                break;
            }
            default:
                out += e;
                break;
            }
        }
    }
    Json parse_value() {
        Json value;
        const char c = peek();
        if (c == '{') {
            value.type = Json::Type::object;
            ++at;
            if (peek() == '}') {
                ++at;
                return value;
            }
            while (true) {
                std::string key = parse_string();
                expect(':');
                value.object[key] = parse_value();
                if (peek() == ',') {
                    ++at;
                    continue;
                }
                expect('}');
                return value;
            }
        }
        if (c == '[') {
            value.type = Json::Type::array;
            ++at;
            if (peek() == ']') {
                ++at;
                return value;
            }
            while (true) {
                value.array.push_back(parse_value());
                if (peek() == ',') {
                    ++at;
                    continue;
                }
                expect(']');
                return value;
            }
        }
        if (c == '"') {
            value.type = Json::Type::string;
            value.string = parse_string();
            return value;
        }
        if (literal("true")) {
            value.type = Json::Type::boolean;
            value.boolean = true;
            return value;
        }
        if (literal("false")) {
            value.type = Json::Type::boolean;
            return value;
        }
        if (literal("null")) {
            return value;
        }
        const char* begin = text.c_str() + at;
        char* end = nullptr;
        value.number = std::strtod(begin, &end);
        if (end == begin) {
            fail("unexpected character");
        }
        value.type = Json::Type::number;
        at += static_cast<std::size_t>(end - begin);
        return value;
    }
};

} // namespace

Json parse_json(const std::string& text) {
    Parser parser{text};
    Json value = parser.parse_value();
    parser.skip_space();
    if (parser.at != text.size()) {
        parser.fail("trailing characters");
    }
    return value;
}

std::string json_quote(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\r':
            out += "\\r";
            break;
        case '\t':
            out += "\\t";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char code[8];
                std::snprintf(code, sizeof code, "\\u%04x", c);
                out += code;
            } else {
                out += c;
            }
        }
    }
    return out + "\"";
}

// ---------------------------------------------------------------------------------------
// Chromium over two pipes

namespace {

std::string base64_decode(const std::string& text) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z')
            return c - 'A';
        if (c >= 'a' && c <= 'z')
            return c - 'a' + 26;
        if (c >= '0' && c <= '9')
            return c - '0' + 52;
        if (c == '+')
            return 62;
        if (c == '/')
            return 63;
        return -1;
    };
    std::string out;
    unsigned bits = 0;
    int count = 0;
    for (const char c : text) {
        const int v = value(c);
        if (v < 0) {
            continue;
        }
        bits = (bits << 6) | static_cast<unsigned>(v);
        count += 6;
        if (count >= 8) {
            count -= 8;
            out += static_cast<char>((bits >> count) & 0xFF);
        }
    }
    return out;
}

using exactpixels::testing::read_text;

constexpr auto wait_limit = std::chrono::seconds(60);

} // namespace

struct Browser::Impl {
    fs::path profile;
    pid_t pid = -1;
    int to_chrome = -1;   // we write commands here (Chromium's fd 3)
    int from_chrome = -1; // we read answers here (Chromium's fd 4)
    std::string buffer;   // bytes read but not yet split into messages
    int next_id = 1;
    std::string session;
    std::vector<Json> events; // events received while waiting for something else
    std::vector<std::string> console;

    [[noreturn]] void fail(const std::string& what) const {
        std::string log = read_text(profile / "chromium.log");
        if (log.size() > 2000) {
            log = log.substr(log.size() - 2000);
        }
        throw std::runtime_error("Chromium: " + what + "\n--- chromium.log (end) ---\n" +
                                 log);
    }

    void start(int width, int height) {
        std::signal(SIGPIPE, SIG_IGN);
        fs::remove_all(profile);
        fs::create_directories(profile);
        int commands[2], answers[2];
        if (::pipe(commands) != 0 || ::pipe(answers) != 0) {
            fail("pipe() failed");
        }
        const char* env = std::getenv("EXACTPIXELS_CHROMIUM");
        const std::string program = env != nullptr && *env != '\0' ? env : "chromium";
        const std::string size =
            "--window-size=" + std::to_string(width) + "," + std::to_string(height);
        const std::string data = "--user-data-dir=" + (profile / "data").string();
        std::vector<std::string> args = {
            program,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-dev-shm-usage",
            "--remote-debugging-pipe",
            "--no-first-run",
            "--no-default-browser-check",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-extensions",
            "--disable-default-apps",
            "--disable-features=Translate,OptimizationHints,MediaRouter",
            "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1",
            "--proxy-server=127.0.0.1:9",
            "--hide-scrollbars",
            "--force-device-scale-factor=1",
            size,
            data,
            "about:blank"};
        const std::string log = (profile / "chromium.log").string();
        pid = ::fork();
        if (pid < 0) {
            fail("fork() failed");
        }
        if (pid == 0) {
            // The child: commands arrive on fd 3, answers leave on fd 4.
            const int read_end = ::dup(commands[0]);
            const int write_end = ::dup(answers[1]);
            ::dup2(read_end, 3);
            ::dup2(write_end, 4);
            const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            ::dup2(out, 1);
            ::dup2(out, 2);
            const int devnull = ::open("/dev/null", O_RDONLY);
            ::dup2(devnull, 0);
            for (int fd = 5; fd < 256; ++fd) {
                ::close(fd);
            }
            std::vector<char*> argv;
            for (auto& arg : args) {
                argv.push_back(arg.data());
            }
            argv.push_back(nullptr);
            ::execvp(argv[0], argv.data());
            const std::string message = "cannot run " + program + ": " +
                                        std::strerror(errno) +
                                        " (install Debian's chromium package)\n";
            (void)!::write(2, message.data(), message.size());
            ::_exit(127);
        }
        ::close(commands[0]);
        ::close(answers[1]);
        to_chrome = commands[1];
        from_chrome = answers[0];
        ::fcntl(to_chrome, F_SETFD, FD_CLOEXEC);
        ::fcntl(from_chrome, F_SETFD, FD_CLOEXEC);

        const Json target =
            call("Target.createTarget", R"({"url":"about:blank"})", false);
        const Json attached = call("Target.attachToTarget",
                                   R"({"flatten":true,"targetId":)" +
                                       json_quote(target["targetId"].str()) + "}",
                                   false);
        session = attached["sessionId"].str();
        if (session.empty()) {
            fail("no session for the new tab");
        }
        call("Page.enable", "{}");
        call("Runtime.enable", "{}");
        call("Log.enable", "{}");
        call("Emulation.setDeviceMetricsOverride",
             R"({"deviceScaleFactor":1,"mobile":false,"width":)" + std::to_string(width) +
                 R"(,"height":)" + std::to_string(height) + "}");
    }

    void send(const std::string& message) {
        std::string data = message;
        data += '\0';
        std::size_t done = 0;
        while (done < data.size()) {
            const ssize_t n = ::write(to_chrome, data.data() + done, data.size() - done);
            if (n <= 0) {
                fail("the browser closed its command pipe");
            }
            done += static_cast<std::size_t>(n);
        }
    }

    // The next message from Chromium; fails after the wait limit.
    Json receive() {
        const auto deadline = std::chrono::steady_clock::now() + wait_limit;
        while (true) {
            const auto nul = buffer.find('\0');
            if (nul != std::string::npos) {
                const std::string text = buffer.substr(0, nul);
                buffer.erase(0, nul + 1);
                return parse_json(text);
            }
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0) {
                fail("no answer within 60 s");
            }
            pollfd p{from_chrome, POLLIN, 0};
            const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
            if (ready < 0 && errno == EINTR) {
                continue;
            }
            if (ready <= 0) {
                continue;
            }
            char chunk[65536];
            const ssize_t n = ::read(from_chrome, chunk, sizeof chunk);
            if (n <= 0) {
                fail("the browser exited (is Debian's chromium package installed?)");
            }
            buffer.append(chunk, static_cast<std::size_t>(n));
        }
    }

    // Records what a console-related event says; keeps every event for wait_for().
    void note(const Json& event) {
        const std::string& method = event["method"].str();
        const Json& params = event["params"];
        if (method == "Runtime.exceptionThrown") {
            const Json& details = params["exceptionDetails"];
            std::string text = details["exception"]["description"].str();
            if (text.empty()) {
                text = details["text"].str();
            }
            console.push_back("uncaught exception: " + text);
        } else if (method == "Runtime.consoleAPICalled") {
            const std::string& type = params["type"].str();
            if (type == "error" || type == "assert") {
                std::string text;
                for (const auto& arg : params["args"].array) {
                    text += (text.empty() ? "" : " ") +
                            (arg["value"].type == Json::Type::string
                                 ? arg["value"].string
                                 : arg["description"].str());
                }
                console.push_back("console." + type + ": " + text);
            }
        } else if (method == "Log.entryAdded") {
            const Json& entry = params["entry"];
            if (entry["level"].str() == "error") {
                std::string text = entry["text"].str();
                if (!entry["url"].str().empty()) {
                    text += " (" + entry["url"].str() + ")";
                }
                console.push_back(entry["source"].str() + " error: " + text);
            }
        }
        events.push_back(event);
    }

    // Sends a command and waits for its answer; fails on a protocol error.
    Json call(const std::string& method, const std::string& params, bool in_tab = true) {
        const int id = next_id++;
        std::string message = "{\"id\":" + std::to_string(id) +
                              ",\"method\":" + json_quote(method) +
                              ",\"params\":" + params;
        if (in_tab) {
            message += ",\"sessionId\":" + json_quote(session);
        }
        send(message + "}");
        while (true) {
            Json answer = receive();
            if (answer["id"].type == Json::Type::number &&
                static_cast<int>(answer["id"].number) == id) {
                if (answer.has("error")) {
                    fail(method + ": " + answer["error"]["message"].str());
                }
                return answer["result"];
            }
            if (answer.has("method")) {
                note(answer);
            }
        }
    }

    // Waits for the event `method` of this tab (it may already have arrived).
    void wait_for(const std::string& method) {
        while (true) {
            for (auto it = events.begin(); it != events.end(); ++it) {
                if ((*it)["method"].str() == method) {
                    events.erase(events.begin(), it + 1);
                    return;
                }
            }
            Json message = receive();
            if (message.has("method")) {
                note(message);
            }
        }
    }

    void stop() {
        if (pid <= 0) {
            return;
        }
        try {
            send(R"({"id":999999,"method":"Browser.close","params":{}})");
        } catch (const std::exception&) {
        }
        ::close(to_chrome);
        ::close(from_chrome);
        // Give Chromium up to 10 s to exit by itself, then end it.
        for (int i = 0; i < 100; ++i) {
            int status = 0;
            if (::waitpid(pid, &status, WNOHANG) == pid) {
                pid = -1;
                break;
            }
            ::usleep(100000);
        }
        if (pid > 0) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, nullptr, 0);
        }
        std::error_code ignored;
        fs::remove_all(profile, ignored);
    }
};

Browser::Browser(const fs::path& profile, int width, int height)
    : impl_(std::make_unique<Impl>()) {
    impl_->profile = profile;
    try {
        impl_->start(width, height);
    } catch (...) {
        impl_->stop();
        throw;
    }
}

Browser::~Browser() {
    impl_->stop();
}

PageVisit Browser::open(const std::string& url, const std::string& script,
                        const fs::path& screenshot) {
    Impl& b = *impl_;
    b.events.clear();
    b.console.clear();
    PageVisit visit;
    const Json navigated = b.call("Page.navigate", "{\"url\":" + json_quote(url) + "}");
    visit.error = navigated["errorText"].str();
    if (!visit.error.empty()) {
        return visit;
    }
    b.wait_for("Page.loadEventFired");
    b.call(
        "Runtime.evaluate",
        R"cdp({"expression":"document.fonts.ready.then(() => true)","awaitPromise":true})cdp");
    try {
        visit.result = evaluate(script);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(std::string(e.what()) + " (the check script, on " + url + ")");
    }
    if (!screenshot.empty()) {
        const Json shot = b.call("Page.captureScreenshot", R"({"format":"png"})");
        fs::create_directories(screenshot.parent_path());
        std::ofstream(screenshot, std::ios::binary) << base64_decode(shot["data"].str());
    }
    visit.console = b.console;
    return visit;
}

Json Browser::evaluate(const std::string& script) {
    Impl& b = *impl_;
    const Json evaluated =
        b.call("Runtime.evaluate", "{\"expression\":" + json_quote(script) +
                                       ",\"returnByValue\":true,\"awaitPromise\":true}");
    if (evaluated.has("exceptionDetails")) {
        const Json& details = evaluated["exceptionDetails"];
        b.fail("a script failed on the page: " + details["exception"]["description"].str() +
               details["text"].str());
    }
    return evaluated["result"]["value"];
}

Json Browser::command(const std::string& method, const std::string& params) {
    return impl_->call(method, params);
}

void Browser::screenshot(const std::string& selector, const fs::path& png) {
    const Json box = evaluate("(() => { const e = document.querySelector(" +
                              json_quote(selector) +
                              "); e.scrollIntoView({block: 'center'});"
                              " const b = e.getBoundingClientRect();"
                              " return {x: b.left + scrollX, y: b.top + scrollY, w: b.width, h: b.height};"
                              " })()");
    const Json shot = command(
        "Page.captureScreenshot",
        R"({"format":"png","clip":{"scale":1,"x":)" + std::to_string(box["x"].number) +
            R"(,"y":)" + std::to_string(box["y"].number) + R"(,"width":)" +
            std::to_string(box["w"].number) + R"(,"height":)" +
            std::to_string(box["h"].number) + "}}");
    fs::create_directories(png.parent_path());
    std::ofstream(png, std::ios::binary) << base64_decode(shot["data"].str());
}

std::vector<std::string> Browser::console() {
    // Collect what has arrived by now: a round trip makes Chromium send pending events.
    impl_->call("Runtime.evaluate", R"({"expression":"0"})");
    return impl_->console;
}

} // namespace exactpixels::bookcheck
