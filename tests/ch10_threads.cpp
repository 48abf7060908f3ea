// Chapter 10 tests of the threads: the worker pool runs a job once on every thread, the
// caller included, waits for all of them and hands a worker's exception to the caller;
// the tiled renderer that keeps its pool and bins between draws, binning in parallel,
// draws the teaching path's picture with 1, 2, 3 and 7 threads on the random, mesh and
// fan sets, with and without depth, however often it is reused.
#include "ch02_grid.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/fast/tiled_rasterizer.hpp"
#include "exactpixels/fast/worker_pool.hpp"
#include "support/printing.hpp"
#include "support/meshes.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

using namespace exactpixels;

TEST_CASE("a worker pool runs the job once on every thread and waits for all of them") {
    for (const int threads : {1, 2, 3, 7}) {
        INFO(threads << " threads");
        WorkerPool pool(threads);
        CHECK(pool.size() == threads);
        const std::thread::id caller = std::this_thread::get_id();
        std::vector<int> runs(static_cast<std::size_t>(threads), 0);
        std::vector<std::thread::id> ids(static_cast<std::size_t>(threads));
        for (int round = 1; round <= 300; ++round) {
            pool.run([&](int t) {
                if (t != 0) { // a worker that is late must still be waited for
                    std::this_thread::yield();
                }
                ++runs[static_cast<std::size_t>(t)];
                ids[static_cast<std::size_t>(t)] = std::this_thread::get_id();
            });
            // Every thread ran exactly once in this round, and had finished by now.
            REQUIRE(runs == std::vector<int>(static_cast<std::size_t>(threads), round));
        }
        CHECK(ids[0] == caller); // thread 0 is the caller
        const std::set<std::thread::id> distinct(ids.begin(), ids.end());
        CHECK(distinct.size() == static_cast<std::size_t>(threads)); // one thread each
    }
}

TEST_CASE("a worker pool hands on the lowest thread's exception after all finished") {
    WorkerPool pool(4);
    std::atomic<int> finished{0};
    try {
        pool.run([&](int t) {
            if (t == 0) { // the caller, slower than the throwers
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
            }
            ++finished;
            if (t >= 2) {
                throw Error("thread " + std::to_string(t));
            }
        });
        FAIL("no Error");
    } catch (const Error& e) {
        CHECK(std::string(e.what()) == "thread 2");
        CHECK(finished == 4); // nobody was still running when the caller saw it
    }
    // The pool still works after a failed run, and forgets the old exceptions.
    std::atomic<int> ran{0};
    pool.run([&](int) { ++ran; });
    CHECK(ran == 4);
    CHECK_THROWS_WITH_AS(WorkerPool(0), "thread count 0 is outside 1 .. 64", Error);
    CHECK_THROWS_AS(WorkerPool(max_threads + 1), Error);
}

TEST_CASE("the shared pool runs every index once at any count, inside itself and "
          "beside another caller") {
    const auto check_run = [](int threads) { // each index exactly once, all finished
        std::vector<std::atomic<int>> runs(static_cast<std::size_t>(threads));
        run_on_shared_pool(threads, [&](int t) { ++runs[static_cast<std::size_t>(t)]; });
        return std::all_of(runs.begin(), runs.end(), [](const auto& n) { return n == 1; });
    };
    for (const int threads : {2, 3, 2, 1, 7, 7}) { // the pool remade when the count changes
        INFO(threads << " threads");
        CHECK(check_run(threads));
    }
    // A job that asks for threads of its own gets a pool of its own: no deadlock.
    std::atomic<int> inner{0};
    run_on_shared_pool(2, [&](int t) {
        if (t == 1) {
            inner += check_run(3) ? 1 : 0;
        }
    });
    CHECK(inner == 1);
    // Two callers at once: one runs on the shared pool, the other on a pool of its own.
    std::atomic<int> good{0};
    const auto caller = [&] {
        for (int round = 0; round < 50; ++round) {
            good += check_run(2) ? 1 : 0;
        }
    };
    std::thread other(caller);
    caller();
    other.join();
    CHECK(good == 100);
    // The lowest index's exception, and the pool works after it.
    CHECK_THROWS_WITH_AS(run_on_shared_pool(3,
                                            [](int t) {
                                                if (t >= 1) {
                                                    throw Error("thread " +
                                                                std::to_string(t));
                                                }
                                            }),
                         "thread 1", Error);
    CHECK(check_run(3));
}

TEST_CASE("thread shares split a list of lists evenly and in order") {
    const std::vector<std::size_t> sizes = {5, 0, 3, 9, 1, 0};
    for (const int threads : {1, 2, 3, 7, 19}) {
        INFO(threads << " threads");
        std::vector<std::pair<std::size_t, std::size_t>> seen; // (list, item), in order
        for (int t = 0; t < threads; ++t) {
            std::size_t items = 0;
            for_thread_stretch(sizes, t, threads,
                               [&](std::size_t i, std::size_t first, std::size_t end) {
                                   CHECK(first < end);
                                   CHECK(end <= sizes[i]);
                                   for (std::size_t k = first; k < end; ++k) {
                                       seen.emplace_back(i, k);
                                   }
                                   items += end - first;
                               });
            CHECK(items == thread_share(18, t + 1, threads) - thread_share(18, t, threads));
        }
        std::vector<std::pair<std::size_t, std::size_t>> all;
        for (std::size_t i = 0; i < sizes.size(); ++i) {
            for (std::size_t k = 0; k < sizes[i]; ++k) {
                all.emplace_back(i, k);
            }
        }
        CHECK(seen == all); // every item once, in order
    }
}

namespace {

/// The colour and depth buffers after `how` drew into a width x height target.
template <class How>
std::pair<std::vector<Rgba8>, std::vector<float>> draw(int width, int height,
                                                       bool with_depth, How&& how) {
    std::vector<Rgba8> colour(static_cast<std::size_t>(width * height), rgba(0, 0, 0));
    std::vector<float> z(static_cast<std::size_t>(width * height), 1.0f);
    how(RenderTarget{colour.data(), with_depth ? z.data() : nullptr, width, height});
    return {colour, z};
}

/// Flat triangles for the snapped vertices of `set`: random colours and depths.
std::vector<FlatTriangle> flat(const std::vector<std::array<FixedPoint2, 3>>& set,
                               std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> depth(0.0f, 1.0f);
    std::uniform_int_distribution<int> byte(1, 255);
    std::vector<FlatTriangle> tris;
    for (const auto& v : set) {
        tris.push_back({v, depth_plane(v, {depth(rng), depth(rng), depth(rng)}),
                        rgba(static_cast<std::uint8_t>(byte(rng)),
                             static_cast<std::uint8_t>(byte(rng)),
                             static_cast<std::uint8_t>(byte(rng)))});
    }
    return tris;
}

} // namespace

TEST_CASE("a kept tiled renderer draws the teaching path's picture with 1 to 7 threads") {
    // The random set (overlapping triangles of every size, many crossing tiles), chapter
    // 2's jittered mesh and its fan of slivers, each drawn flat and depth-tested by one
    // renderer per thread count, reused for every set, both target sizes (so its bins
    // are reused for another tile count) and sets smaller than its thread count.
    std::mt19937_64 rng(1909);
    std::vector<std::array<FixedPoint2, 3>> random;
    for (int n = 0; n < 2000; ++n) {
        const double spread = n % 3 == 0 ? 8.0 : n % 3 == 1 ? 70.0 : 350.0;
        random.push_back(n % 5 == 4 ? ch02::random_tie_triangle(rng, -10, 330)
                                    : ch02::random_triangle(rng, -spread / 4, spread));
    }
    std::uniform_real_distribution<double> wobble(-3.0, 3.0);
    const auto jittered = [&](int, int) { return Point2{wobble(rng), wobble(rng)}; };
    const auto mesh = testing::grid_mesh({7.3, 5.7}, 14, 21.0, jittered);
    const auto fan = testing::sliver_fan({150.5, 110.5}, 100.0, 720);
    const std::vector<std::pair<const char*, std::vector<FlatTriangle>>> sets{
        {"random", flat(random, 1)},
        {"mesh", flat(mesh, 2)},
        {"fan", flat(fan, 3)},
        {"two triangles", flat({random[2], random[5]}, 4)},
        {"none", {}}};
    for (const int threads : {1, 2, 3, 7}) {
        TiledRenderer renderer(threads);
        CHECK(renderer.threads() == threads);
        for (const auto& size : {std::pair{320, 240}, std::pair{130, 70}}) {
            const int width = size.first;
            const int height = size.second;
            for (const auto& set : sets) {
                const char* name = set.first;
                const std::vector<FlatTriangle>& tris = set.second;
                for (const bool with_depth : {false, true}) {
                    INFO(threads << " threads, " << std::string(name) << ", " << width
                                 << " x " << height << ", depth test: " << with_depth);
                    const auto reference =
                        draw(width, height, with_depth,
                             [&](const RenderTarget& t) { draw_reference(t, tris); });
                    REQUIRE(draw(width, height, with_depth, [&](const RenderTarget& t) {
                                renderer.draw(t, tris);
                            }) == reference);
                }
            }
        }
    }
    // The sets are not trivial: most of the larger target is drawn by each.
    for (const char* name : {"random", "mesh", "fan"}) {
        INFO(name);
        const auto& tris = std::find_if(sets.begin(), sets.end(), [&](const auto& s) {
                               return std::string(s.first) == name;
                           })->second;
        const auto picture = draw(
            320, 240, false, [&](const RenderTarget& t) { draw_reference(t, tris); });
        int drawn = 0;
        for (const Rgba8 p : picture.first) {
            drawn += p != rgba(0, 0, 0);
        }
        CHECK(drawn > 320 * 240 / 4);
    }
}

TEST_CASE("a kept tiled renderer rejects a bad vertex before drawing and draws after") {
    std::vector<Rgba8> colour(64 * 64, rgba(1, 2, 3));
    const RenderTarget t{colour.data(), nullptr, 64, 64};
    const std::array<FixedPoint2, 3> ok = ch02::snap3({1, 1}, {60, 2}, {30, 50});
    const std::int64_t past = max_fixed_coordinate + 1;
    const std::vector<FlatTriangle> bad{
        {ok, {}, rgba(255, 0, 0)},
        {{FixedPoint2{0, 0}, FixedPoint2{past, 0}, FixedPoint2{0, 256}}, {}, {}}};
    TiledRenderer renderer(3);
    try {
        renderer.draw(t, bad);
        FAIL("no Error");
    } catch (const Error& e) {
        CHECK(std::string(e.what()).find("triangle 1: vertex 1") == 0);
    }
    CHECK(colour == std::vector<Rgba8>(64 * 64, rgba(1, 2, 3))); // nothing drawn
    renderer.draw(t, std::span(bad).first(1));                   // still usable
    CHECK(colour[static_cast<std::size_t>(10 * 64 + 30)] == rgba(255, 0, 0));
}
