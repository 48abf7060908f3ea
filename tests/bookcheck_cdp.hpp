// bookcheck_cdp.hpp: a headless Chromium driven over the DevTools protocol, for the
// checks of the built book (tests/bookcheck_html.cpp).
//
//   Browser browser(profile_folder, 1200, 900);          // starts `chromium --headless`
//   auto page = browser.open("file:///.../01-x.html", script, "shot.png");
//   page.result   // what `script` (a JavaScript expression) evaluated to, as JSON
//   page.console  // every console error, uncaught exception and failed load
//
// Chromium runs with a fresh profile (the folder is created empty and removed afterwards)
// and no network: background services are off and every host name resolves to nothing
// (only 127.0.0.1 is reachable, for a web server on this machine).
// The protocol runs over two pipes (--remote-debugging-pipe: commands on fd 3, answers
// on fd 4, each message a JSON text ended by a NUL byte), so no port is opened.
// The program is `chromium` on PATH, or $EXACTPIXELS_CHROMIUM.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace exactpixels::bookcheck {

/// A JSON value: just enough to read what Chromium sends.
struct Json {
    enum class Type { null, boolean, number, string, array, object };
    Type type = Type::null;          ///< which of the members below holds the value
    bool boolean = false;            ///< the value when type is boolean
    double number = 0;               ///< the value when type is number
    std::string string;              ///< the value when type is string (UTF-8)
    std::vector<Json> array;         ///< the items when type is array
    std::map<std::string, Json> object; ///< the members when type is object

    /// The member `key`, or a null value when this is not an object or has no such key.
    const Json& operator[](const std::string& key) const;
    /// True when this is an object with member `key`.
    bool has(const std::string& key) const;
    /// The string value, or "" when this is not a string.
    const std::string& str() const;
};

/// Parses one JSON text; throws std::runtime_error on malformed input.
Json parse_json(const std::string& text);

/// `text` as a JSON string literal, quotes included.
std::string json_quote(const std::string& text);

/// What opening one page produced.
struct PageVisit {
    std::string error;                ///< the navigation error (e.g. a missing file), or ""
    Json result;                      ///< the value of the script, evaluated after load
    std::vector<std::string> console; ///< console errors, exceptions and failed loads
};

/// One headless Chromium with one tab.
class Browser {
public:
    /// Starts Chromium with a fresh profile in `profile` and a `width` x `height` viewport.
    Browser(const std::filesystem::path& profile, int width, int height);
    ~Browser();
    Browser(const Browser&) = delete;
    Browser& operator=(const Browser&) = delete;

    /// Loads `url`, waits for its load event and web fonts, evaluates `script` and, when
    /// `screenshot` is not empty, saves the first screen as PNG there.
    PageVisit open(const std::string& url, const std::string& script,
                   const std::filesystem::path& screenshot = {});

    /// Evaluates `script` (a JavaScript expression; a promise is awaited) in the page
    /// open now and returns its value as JSON; throws if it throws.
    Json evaluate(const std::string& script);

    /// Sends the DevTools command `method` with `params` (a JSON object) to the page open
    /// now, e.g. Input.dispatchMouseEvent, and returns its result.
    Json command(const std::string& method, const std::string& params);

    /// Saves the element `selector` of the page open now, scrolled into view, as PNG.
    void screenshot(const std::string& selector, const std::filesystem::path& png);

    /// Console errors, uncaught exceptions and failed loads since the last open().
    std::vector<std::string> console();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace exactpixels::bookcheck
