#include <xeno/xeno.hpp>

#include <cstdio>

int main() {
    namespace xs = xeno::f64;  // or xeno::f32: the same names in single precision
    const xs::Quat turn = xs::Quat::from_axis_angle(xs::Vec3{0, 1, 0}, 3.14159265358979 / 2);
    const xs::Transform pose{{1, 2, 3}, turn};
    const xs::Vec3 p = pose.apply(xs::Vec3{0, 0, 1});
    std::printf("(0, 0, 1) in the world: (%.3f, %.3f, %.3f)\n", p.x, p.y, p.z);
}
