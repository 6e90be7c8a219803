#include <xeno/xeno.hpp>

#include <algorithm>
#include <cstdio>
#include <future>
#include <vector>

// The game's job system as xeno sees it: "run this range function over [0, count) and wait".
// std::async stands in for the game's own jobs here.
class GameJobs final : public xeno::TaskSystem {
public:
    unsigned workers() const override { return 4; }
    void parallel_for(std::uint32_t count, std::uint32_t min_range, xeno::RangeTask task) override {
        const std::uint32_t size = std::max(min_range, (count + 3) / 4);
        std::vector<std::future<void>> jobs;
        for (std::uint32_t begin = size; begin < count; begin += size)
            jobs.push_back(std::async(std::launch::async, task, begin, std::min(count, begin + size)));
        task(0, std::min(count, size));  // the calling thread takes the first range
        for (std::future<void>& job : jobs) job.get();
    }
};

int main() {
    namespace xs = xeno::f32;
    GameJobs jobs;
    xs::World on_jobs, on_one;
    on_jobs.set_task_system(&jobs);  // or on_jobs.set_workers(2): xeno's own thread pool
    for (xs::World* world : {&on_jobs, &on_one}) {
        xs::BodyDef ground;
        ground.type = xeno::BodyType::static_body;
        ground.position = {0, -0.5f, 0};
        world->create_body(xs::Box(20, 0.5f, 20), ground);
        for (int i = 0; i < 400; ++i) {
            xs::BodyDef box;
            box.position = {float(i % 20) - 10, 0.5f + 1.1f * float(i / 100), float(i / 20 % 5) - 2};
            world->create_body(xs::Box(0.5f, 0.5f, 0.5f), box);
        }
        for (int step = 0; step < 120; ++step) world->step(1.0f / 60);
    }
    bool same = true;  // any job system gives the bits of one thread
    on_one.for_each_body([&](xeno::BodyId id, const xs::Body& b) {
        same = same && b.position() == on_jobs.body(id).position() && b.orientation() == on_jobs.body(id).orientation();
    });
    std::printf("400 boxes, 2 s on the game's jobs: %s one thread's result\n", same ? "the same bits as" : "DIFFERENT from");
    return same ? 0 : 1;
}
