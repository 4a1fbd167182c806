#include "storage/processor_sharing.hpp"

#include "engine/check.hpp"
#include "storage/precision.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pagecache::detail {

ProcessorSharing::ProcessorSharing(Simulator& sim, EventCallback flow_due, EventCallback head_due,
                                   void* head_context)
    : sim_(&sim), flow_due_(flow_due), head_due_(head_due), head_context_(head_context) {}

ProcessorSharing::~ProcessorSharing() { cancel_events(); }

void ProcessorSharing::cancel_events() noexcept {
  // Without events it does not touch the simulator, which may be gone (see ~FairShare).
  if (head_event_) sim_->cancel(head_event_);
  for (const KeyedFlow& entry : bounded_) sim_->cancel(entry.flow->completion);
}

void ProcessorSharing::advance() noexcept {
  const double now = sim_->now();
  if (!sharing_.empty() && now > updated_) virtual_time_ += level_ * (now - updated_);
  updated_ = now;
}

void ProcessorSharing::insert_sharing(FlowState* flow, double remaining) {
  flow->mode = FlowMode::Sharing;
  flow->virtual_finish = virtual_time_ + std::max(remaining, 0.0) / flow->weight;
  sharing_.push({flow->virtual_finish, flow->sequence, flow});
  // An unbounded flow can never be capped: it need not be found by threshold.
  if (std::isfinite(flow->threshold)) sharing_threshold_.push({flow->threshold, flow->sequence, flow});
  sharing_weighted_cost_ += flow->cost() * flow->weight;
}

double ProcessorSharing::erase_sharing(FlowState* flow) {
  const double remaining = std::max(0.0, (flow->virtual_finish - virtual_time_) * flow->weight);
  sharing_.erase(flow->finish_index);
  if (std::isfinite(flow->threshold)) sharing_threshold_.erase(flow->sharing_threshold_index);
  if (sharing_.empty()) {
    // Renormalise: keeps V small, and the sum free of accumulated rounding.
    virtual_time_ = 0.0;
    sharing_weighted_cost_ = 0.0;
  } else {
    sharing_weighted_cost_ -= flow->cost() * flow->weight;
  }
  return remaining;
}

void ProcessorSharing::insert_bounded(FlowState* flow, double remaining) {
  flow->mode = FlowMode::Bounded;
  flow->remaining = std::max(remaining, 0.0);
  flow->rate = flow->bound;
  flow->updated = sim_->now();
  if (bounded_ordered_) bounded_.push({flow->threshold, flow->sequence, flow});
  else bounded_.push_unordered({flow->threshold, flow->sequence, flow});
  bounded_usage_ += flow->cost() * flow->bound;
  flow->completion = sim_->schedule_at(sim_->now() + flow->remaining / flow->rate, flow_due_, flow);
}

double ProcessorSharing::erase_bounded(FlowState* flow) {
  if (bounded_ordered_) bounded_.erase(flow->bounded_threshold_index);
  else bounded_.erase_unordered(flow->bounded_threshold_index);
  if (bounded_.empty()) bounded_ordered_ = false;
  bounded_usage_ = bounded_.empty() ? 0.0 : bounded_usage_ - flow->cost() * flow->bound;
  sim_->cancel(flow->completion);
  return std::max(0.0, flow->remaining_at(sim_->now()));
}

void ProcessorSharing::add(FlowState* flow, double remaining) {
  advance();
  // A flow whose bound is below the level it would leave the others joins the bounded group
  // at once (a memory copy at its per-thread bound, the common case): rebalance would move
  // it there anyway, after two heap insertions and two removals.
  const double usage_with_it = bounded_usage_ + flow->cost() * flow->bound;
  const double level_with_it = sharing_.empty() ? (usage_with_it <= 1.0 ? kUnbounded : -kUnbounded)
                                                : (1.0 - usage_with_it) / sharing_weighted_cost_;
  if (std::isfinite(flow->threshold) && level_with_it > 0.0 && flow->threshold < level_with_it * (1.0 - precision::kRelativeRate)) {
    insert_bounded(flow, remaining);
  } else {
    insert_sharing(flow, remaining);
  }
  rebalance();
  schedule_head();
}

void ProcessorSharing::remove(FlowState* flow) {
  advance();
  if (flow->mode == FlowMode::Sharing) {
    erase_sharing(flow);
  } else {
    PC_ASSERT(flow->mode == FlowMode::Bounded);
    erase_bounded(flow);
  }
  rebalance();
  schedule_head();
}

void ProcessorSharing::take_finished(std::vector<FlowState*>& finished) {
  head_event_.reset();  // it is firing now
  advance();
  PC_ASSERT(!sharing_.empty());
  // The head is due now by construction; pin V to it so rounding cannot leave it running.
  virtual_time_ = std::max(virtual_time_, sharing_.top().key);
  while (!sharing_.empty() && sharing_.top().key <= virtual_time_) {
    FlowState* flow = sharing_.top().flow;
    erase_sharing(flow);
    finished.push_back(flow);
  }
  rebalance();
  schedule_head();
}

void ProcessorSharing::rebalance() {
  // Move the boundary between the bounded prefix and the sharing suffix (in threshold order)
  // until max threshold(bounded) <= t <= min threshold(sharing). Each move is in the right
  // direction (the usage at level t is monotone in t), so the walk ends; the relative
  // tolerance keeps ties from being moved back and forth by rounding noise.
  const double now = sim_->now();
  for (;;) {
    double level;
    if (sharing_.empty()) {
      level = bounded_usage_ <= 1.0 + precision::kRelativeRate ? kUnbounded : -kUnbounded;
    } else {
      level = (1.0 - bounded_usage_) / sharing_weighted_cost_;
    }
    if (!sharing_threshold_.empty() && sharing_threshold_.top().key < level * (1.0 - precision::kRelativeRate)) {
      FlowState* flow = sharing_threshold_.top().flow;
      insert_bounded(flow, erase_sharing(flow));
      continue;
    }
    // At an infinite level no bound is above it: the bounded flows need no order.
    if (!bounded_.empty() && level != kUnbounded && (level <= 0.0 || top_bounded().key > level * (1.0 + precision::kRelativeRate))) {
      FlowState* flow = top_bounded().flow;
      const double remaining = erase_bounded(flow);
      insert_sharing(flow, remaining);
      continue;
    }
    level_ = level;
    break;
  }
  PC_ASSERT(sharing_.empty() || level_ > 0.0);
  updated_ = now;
}

// The bounded flow with the highest threshold (the latest started of equals), ordering the
// group first if it was not. The order, once made, is kept until the group empties: a
// resource near saturation asks at every change.
const KeyedFlow& ProcessorSharing::top_bounded() noexcept {
  if (!bounded_ordered_) {
    bounded_.make_ordered();
    bounded_ordered_ = true;
  }
  return bounded_.top();
}

void ProcessorSharing::schedule_head() {
  if (sharing_.empty()) {
    sim_->cancel(head_event_);
    return;
  }
  const double now = sim_->now();
  const double due = now + std::max(0.0, sharing_.top().key - virtual_time_) / level_;
  if (head_event_) sim_->reschedule(head_event_, due);
  else head_event_ = sim_->schedule_at(due, head_due_, head_context_);
}

double ProcessorSharing::rate(const FlowState* flow) const noexcept {
  return flow->mode == FlowMode::Sharing ? flow->weight * level_ : flow->rate;
}

double ProcessorSharing::usage() const noexcept {
  return bounded_usage_ + (sharing_.empty() ? 0.0 : level_ * sharing_weighted_cost_);
}

void ProcessorSharing::check() const {
  double sharing_cost = 0.0;
  double min_sharing_threshold = kUnbounded;
  for (const KeyedFlow& entry : sharing_) {
    const FlowState* flow = entry.flow;
    PC_ASSERT(entry.key == flow->virtual_finish);
    PC_ASSERT(flow->mode == FlowMode::Sharing);
    sharing_cost += flow->cost() * flow->weight;
    min_sharing_threshold = std::min(min_sharing_threshold, flow->threshold);
  }
  double bounded_cost = 0.0;
  double max_bounded_threshold = 0.0;
  for (const KeyedFlow& entry : bounded_) {
    const FlowState* flow = entry.flow;
    PC_ASSERT(flow->mode == FlowMode::Bounded);
    PC_ASSERT(static_cast<bool>(flow->completion));
    bounded_cost += flow->cost() * flow->bound;
    max_bounded_threshold = std::max(max_bounded_threshold, flow->threshold);
  }
  PC_ASSERT(sharing_threshold_.size() <= sharing_.size());
  PC_ASSERT(!bounded_ordered_ || bounded_.ordered());
  for (std::size_t i = 0; i < bounded_.size(); ++i) {
    PC_ASSERT(bounded_.at(static_cast<HighestThresholdFirst::Index>(i)).flow->bounded_threshold_index == i);
  }
  const auto close = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)}); };
  PC_ASSERT_MSG(close(sharing_cost, sharing_weighted_cost_),
                fmt::format("sharing cost {} vs {}", sharing_cost, sharing_weighted_cost_));
  PC_ASSERT_MSG(close(bounded_cost, bounded_usage_), fmt::format("bounded usage {} vs {}", bounded_cost, bounded_usage_));
  PC_ASSERT(usage() <= 1.0 + 1e-9);
  if (!sharing_.empty()) {
    PC_ASSERT(static_cast<bool>(head_event_));
    PC_ASSERT(max_bounded_threshold <= level_ * (1.0 + 1e-9));
    PC_ASSERT(min_sharing_threshold >= level_ * (1.0 - 1e-9));
  } else {
    PC_ASSERT(!head_event_);
  }
}

}  // namespace pagecache::detail
