// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Contact events (world.hpp, step): which contacts began, persisted or ended in a step, made in
// their places and sorted, merged with the ones recorded between steps, then handed to the
// listener. Included at the end of world.hpp.
#pragma once

#include "world.hpp"

namespace xeno {

// A contact reports an event when it touches or has just stopped touching, except a pair with no
// active body (both asleep, or asleep on a static body): it is not re-collided, its contact is
// unchanged, so "persisted" is not repeated every step.
template <class T>
bool World<T>::makes_event(const Contact<T>& c) const {
    if (!c.touching && !c.was_touching) return false;
    return !(c.touching && c.was_touching && !active(bodies_[c.a.index]) && !active(bodies_[c.b.index]));
}

template <class T>
ContactEvent<T> World<T>::event_of(const Contact<T>& c) const {
    ContactEvent<T> e;
    e.kind = !c.touching ? ContactEventKind::ended : (c.was_touching ? ContactEventKind::persisted : ContactEventKind::began);
    e.a = c.a;
    e.b = c.b;
    e.sensor = c.sensor;
    e.normal = c.manifold.normal;
    e.child_a = c.child_a;
    e.child_b = c.child_b;
    if (c.touching) {
        const Body<T>& a = bodies_[c.a.index];
        const Body<T>& b = bodies_[c.b.index];
        e.count = c.manifold.count;
        for (int i = 0; i < c.manifold.count; ++i) {
            const ContactPoint<T>& p = c.manifold.points[static_cast<std::size_t>(i)];
            e.points[static_cast<std::size_t>(i)] = (a.world_point(p.local_a) + b.world_point(p.local_b)) * T(0.5);
            e.impulse += p.step_impulse;
        }
    }
    return e;
}

// The step's events: the ended events recorded since the last report first, then one per contact
// that makes one, in contact order. On several workers the contacts are cut into fixed blocks,
// each block's events counted and then written into their places in parallel (a 5,050-box
// pyramid makes 15,000 events a step, which took 0.6 ms in float and 1.4 ms in double on one
// thread); the list keeps last step's elements and overwrites them, so only a grown tail is
// cleared first.
template <class T>
std::size_t World<T>::collect_events() {
    const std::size_t recorded = events_pending_.size();
    const std::uint32_t contacts = static_cast<std::uint32_t>(contacts_.size());
    if (workers() <= 1 || contacts < 2 * event_block) {
        events_.swap(events_pending_);
        events_pending_.clear();
        events_.reserve(events_.size() + contacts_.size());
        for (const Contact<T>& c : contacts_)
            if (makes_event(c)) events_.push_back(event_of(c));
        return recorded;
    }
    const std::uint32_t blocks = (contacts + event_block - 1) / event_block;
    const auto block_end = [&](std::uint32_t k) { return std::min(contacts, (k + 1) * event_block); };
    event_block_start_.resize(blocks + std::size_t(1));
    parallel_for(tasks_.get(), blocks, 1u, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t k = begin; k < end; ++k) {
            std::uint32_t count = 0;
            for (std::uint32_t i = k * event_block; i < block_end(k); ++i) count += makes_event(contacts_[i]) ? 1u : 0u;
            event_block_start_[k + 1] = count;
        }
    });
    event_block_start_[0] = static_cast<std::uint32_t>(recorded);
    for (std::uint32_t k = 0; k < blocks; ++k) event_block_start_[k + 1] += event_block_start_[k];
    events_.resize(event_block_start_[blocks]);
    std::copy(events_pending_.begin(), events_pending_.end(), events_.begin());
    events_pending_.clear();
    parallel_for(tasks_.get(), blocks, 1u, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t k = begin; k < end; ++k) {
            std::uint32_t to = event_block_start_[k];
            for (std::uint32_t i = k * event_block; i < block_end(k); ++i)
                if (makes_event(contacts_[i])) events_[to++] = event_of(contacts_[i]);
        }
    });
    return recorded;
}

// The events in pair order. The contacts are in pair order, so their events usually are too, and
// only the ended events recorded between steps (the first `recorded`, few) need a place: they are
// sorted and merged in, O(n), where sorting the whole list took 1 ms a step on the 5,050-box
// pyramid whenever a body had been destroyed. An ended event recorded between steps comes before
// the same pair's event of the step (a slot reused). Only a contact list whose events are not
// strictly increasing (a mesh pair's several contacts) sorts everything, stably: std::sort put a
// reused slot's `began` before the old body's `ended` in any world holding a compound.
template <class T>
void World<T>::sort_events(std::size_t recorded) {
    const auto before = [](const ContactEvent<T>& x, const ContactEvent<T>& y) {
        if (x.a.index != y.a.index) return x.a.index < y.a.index;
        if (x.b.index != y.b.index) return x.b.index < y.b.index;
        return x.child_a != y.child_a ? x.child_a < y.child_a : x.child_b < y.child_b;
    };
    const auto out_of_order = [&](const ContactEvent<T>& x, const ContactEvent<T>& y) { return !before(x, y); };
    const auto steps_events = events_.begin() + static_cast<std::ptrdiff_t>(recorded);
    if (std::adjacent_find(steps_events, events_.end(), out_of_order) != events_.end()) {
        std::stable_sort(events_.begin(), events_.end(), before);
        return;
    }
    if (recorded == 0) return;
    const bool in_order = std::adjacent_find(events_.begin(), steps_events, out_of_order) == steps_events &&
                          (steps_events == events_.end() || before(*(steps_events - 1), *steps_events));
    if (in_order) return;
    std::stable_sort(events_.begin(), steps_events, before);  // in the order they were recorded
    std::vector<ContactEvent<T>>& merged = merged_events_;
    merged.clear();
    std::merge(events_.begin(), steps_events, steps_events, events_.end(), std::back_inserter(merged), before);
    events_.swap(merged);
}

template <class T>
void World<T>::report_events() {
    sort_events(collect_events());
    if (listener_) {
        // The listener may change the world (and so events_; restore_snapshot replaces every
        // member): it is handed a copy held in a local vector, whose buffer is the world's scratch
        // taken out for the call and given back after, so a settled step allocates nothing. Each
        // call holds the listener alive even if it replaces or clears itself.
        std::vector<ContactEvent<T>> delivering;
        delivering.swap(delivered_events_);
        delivering = events_;
        {
            const FlagScope scope(callbacks_.in_listener);
            for (const ContactEvent<T>& e : delivering) {
                if (!listener_) break;  // cleared from inside
                const std::shared_ptr<const Listener> current = listener_;
                (*current)(*this, e);
            }
        }
        delivered_events_.swap(delivering);
    }
}

}  // namespace xeno
