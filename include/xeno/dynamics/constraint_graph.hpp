// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Graph colouring of the contact rows (docs/solver.md, "Colours"): rows of one colour share no
// solver body other than the static stand-in, so they can be solved side by side in SIMD lanes
// and on several threads (task_system.hpp) with the same result as one after another. The greedy rule of
// Box2D v3's constraint graph: each row, in row order, takes the lowest colour that neither of its
// moving bodies has used; a row that finds none goes to the overflow set, solved one by one
// before the colours. Static bodies are slot 0 and take no colour, so a pile on the ground does
// not fill a colour per box. Rebuilt every step from the rows in their (deterministic) order, so
// the same scene gives the same colours whatever happened to memory. Inside a colour the rows are
// listed by their lower moving body, so that the workers, which take a colour in consecutive
// ranges, each keep to the bodies the world placed in their share (World::prepare); the order
// inside a colour changes no result, since its rows share no body.
#pragma once

#include <cstdint>
#include <vector>

namespace xeno {
namespace detail {

/// The rows of one step sorted by colour.
class ConstraintColouring {
public:
    static constexpr int colours = 24;        ///< Box2D v3 uses 24; a box in a pile needs about 8
    std::vector<std::uint32_t> order;         ///< row indices, colour by colour, by lower moving body inside
    std::vector<std::uint32_t> colour_begin;  ///< colours + 1 offsets into order
    std::vector<std::uint32_t> overflow;      ///< rows no colour could take, in row order

    /// Colours `rows` rows whose bodies are body_a(i), body_b(i) (0: static) among `bodies`.
    template <class BodyA, class BodyB>
    void build(std::size_t rows, std::size_t bodies, BodyA body_a, BodyB body_b) {
        used_.assign(bodies, 0u);
        colour_of_.resize(rows);
        colour_begin.assign(colours + 2, 0u);
        overflow.clear();
        for (std::size_t i = 0; i < rows; ++i) {
            const std::uint32_t a = body_a(i), b = body_b(i);
            const std::uint32_t taken = (a != 0 ? used_[a] : 0u) | (b != 0 ? used_[b] : 0u);
            int colour = 0;
            while (colour < colours && (taken >> colour & 1u)) ++colour;
            colour_of_[i] = static_cast<std::uint8_t>(colour);
            if (colour == colours) {
                overflow.push_back(static_cast<std::uint32_t>(i));
                continue;
            }
            if (a != 0) used_[a] |= 1u << colour;
            if (b != 0) used_[b] |= 1u << colour;
            ++colour_begin[static_cast<std::size_t>(colour) + 2];
        }
        // Two counting sorts: the rows by lower moving body, then stably by colour.
        by_body_.assign(bodies + 1, 0u);
        for (std::size_t i = 0; i < rows; ++i) ++by_body_[lower_moving(body_a(i), body_b(i)) + 1u];
        for (std::size_t k = 1; k <= bodies; ++k) by_body_[k] += by_body_[k - 1];
        body_order_.resize(rows);
        for (std::size_t i = 0; i < rows; ++i)
            body_order_[by_body_[lower_moving(body_a(i), body_b(i))]++] = static_cast<std::uint32_t>(i);
        for (int c = 0; c < colours; ++c)
            colour_begin[static_cast<std::size_t>(c) + 2] += colour_begin[static_cast<std::size_t>(c) + 1];
        order.resize(rows - overflow.size());
        for (const std::uint32_t i : body_order_)
            if (colour_of_[i] < colours) order[colour_begin[colour_of_[i] + 1u]++] = i;
        colour_begin.pop_back();
    }
    std::size_t colour_size(int c) const {
        return colour_begin[static_cast<std::size_t>(c) + 1] - colour_begin[static_cast<std::size_t>(c)];
    }

private:
    /// The row's lower body other than the static stand-in (a row has at least one moving body).
    static std::uint32_t lower_moving(std::uint32_t a, std::uint32_t b) { return a == 0 ? b : (b == 0 ? a : (a < b ? a : b)); }

    std::vector<std::uint32_t> used_;        ///< scratch: per solver body, a bit per colour taken
    std::vector<std::uint8_t> colour_of_;    ///< scratch: per row, its colour (colours: overflow)
    std::vector<std::uint32_t> by_body_;     ///< scratch: counting-sort offsets per solver body
    std::vector<std::uint32_t> body_order_;  ///< scratch: the rows by lower moving body
};

}  // namespace detail
}  // namespace xeno
