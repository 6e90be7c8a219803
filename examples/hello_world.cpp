#include <xeno/xeno.hpp>

#include <cstdio>
#include <vector>

int main() {
    namespace xs = xeno::f64;  // or xeno::f32: the same names in single precision
    xs::World world;           // gravity (0, -9.81, 0), fixed steps of 1/60 s

    xs::BodyDef ground;
    ground.type = xeno::BodyType::static_body;
    ground.position = {0, -0.5, 0};  // a 20 m floor whose top is y = 0
    world.create_body(xs::Box(10, 0.5, 10), ground);

    std::vector<xeno::BodyId> boxes;
    for (int i = 0; i < 5; ++i) {
        const xs::Real k = static_cast<xs::Real>(i);  // xs::Real: double here, float in f32
        xs::BodyDef box;                              // dynamic, 1000 kg/m³
        box.position = {xs::Real(0.2) * k, 1 + xs::Real(1.5) * k, 0};
        box.orientation = xs::Quat::from_axis_angle({1, 1, 0}, xs::Real(0.3) * k);
        boxes.push_back(world.create_body(xs::Box(0.5, 0.5, 0.5), box));
    }
    for (int step = 0; step < 180; ++step) world.step(xs::Real(1) / 60);  // three seconds
    for (xeno::BodyId id : boxes) {
        const xs::Vec3 p = world.body(id).position();
        std::printf("box %u rests at (%.3f, %.3f, %.3f)\n", id.index, p.x, p.y, p.z);
    }
}
