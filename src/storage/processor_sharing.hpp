#pragma once
// ProcessorSharing: the max-min share of one resource among flows that cross it alone, in
// O(log n) per change.
//
// With capacity 1 and flow f using cost_f of it per unit of work, the max-min rates are
//   x_f = min(bound_f, weight_f * t)
// for the level t that saturates the resource: sum_f cost_f * x_f = 1 (t = infinity if the
// bounds alone do not saturate it). Flows with threshold bound_f / weight_f below t form the
// *bounded* group and run at their bound; the others form the *sharing* group and run at
// weight_f * t. Because the bounded group is always a prefix of the flows sorted by threshold,
// the level is found by moving the boundary one flow at a time:
//   t = (1 - sum_bounded cost*bound) / sum_sharing cost*weight.
//
// The sharing flows all progress with one virtual clock V (dV/dt = t): flow f is done when V
// reaches V_start + work_f / weight_f. A heap keyed by that virtual finish gives the next
// completion, the only sharing event in the simulator's queue. Bounded flows have constant
// rates and one completion event each.

#include "storage/flow_state.hpp"

#include <pagecache/simulator.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace pagecache::detail {

class ProcessorSharing {
 public:
  /// `flow_due(flow)` runs when a bounded flow is due; `head_due(head_context)` when the
  /// first sharing flow is due.
  ProcessorSharing(Simulator& sim, EventCallback flow_due, EventCallback head_due, void* head_context);
  ProcessorSharing(const ProcessorSharing&) = delete;
  ProcessorSharing& operator=(const ProcessorSharing&) = delete;
  ~ProcessorSharing();

  /// Adds a flow with `remaining` work, at sim.now().
  void add(FlowState* flow, double remaining);
  /// Removes a flow (finished or withdrawn) at sim.now().
  void remove(FlowState* flow);
  /// To be called by the head-due callback: moves the sharing flows that are done into
  /// `finished`, in completion order.
  void take_finished(std::vector<FlowState*>& finished);
  /// Removes every flow, calling visit(flow, remaining work) for each in start order.
  template <class Visit>
  void drain(Visit&& visit);

  std::size_t size() const noexcept { return sharing_.size() + bounded_.size(); }
  bool empty() const noexcept { return size() == 0; }
  /// Current rate of a flow held here.
  double rate(const FlowState* flow) const noexcept;
  /// Fraction of the resource in use.
  double usage() const noexcept;
  /// Throws InvariantError if groups, sums or events disagree with a recomputation.
  void check() const;

 private:
  void advance() noexcept;
  void rebalance();
  void schedule_head();
  void insert_sharing(FlowState* flow, double remaining);
  double erase_sharing(FlowState* flow);
  void insert_bounded(FlowState* flow, double remaining);
  double erase_bounded(FlowState* flow);
  const KeyedFlow& top_bounded() noexcept;
  void cancel_events() noexcept;

  Simulator* sim_;
  EventCallback flow_due_;
  EventCallback head_due_;
  void* head_context_;

  FinishHeap sharing_;                      // sharing flows by virtual finish
  LowestThresholdFirst sharing_threshold_;  // sharing flows with a finite threshold, by threshold
  // Bounded flows by threshold. Only rebalance asks for the highest, and only while the level
  // is finite: until then they are kept unordered (see top_bounded). With 10^5 memory copies
  // in flight, each at its own bound on a memory far from saturated, every insertion into a
  // heap would move a path of entries and write where each went into its flow, long out of cache.
  HighestThresholdFirst bounded_;
  bool bounded_ordered_ = false;
  double sharing_weighted_cost_ = 0.0;      // sum over sharing of cost * weight
  double bounded_usage_ = 0.0;              // sum over bounded of cost * bound
  double level_ = kUnbounded;               // t
  double virtual_time_ = 0.0;               // V
  double updated_ = 0.0;                    // when V was last advanced
  EventHandle head_event_;
};

template <class Visit>
void ProcessorSharing::drain(Visit&& visit) {
  advance();
  std::vector<std::pair<FlowState*, double>> flows;
  flows.reserve(size());
  while (!sharing_.empty()) {
    FlowState* flow = sharing_.top().flow;
    flows.emplace_back(flow, erase_sharing(flow));
  }
  while (!bounded_.empty()) {
    FlowState* flow = bounded_.at(static_cast<HighestThresholdFirst::Index>(bounded_.size() - 1)).flow;
    flows.emplace_back(flow, erase_bounded(flow));
  }
  sharing_weighted_cost_ = 0.0;
  bounded_usage_ = 0.0;
  level_ = kUnbounded;
  cancel_events();
  std::sort(flows.begin(), flows.end(),
            [](const auto& a, const auto& b) { return a.first->sequence < b.first->sequence; });
  for (auto& [flow, remaining] : flows) visit(flow, remaining);
}

}  // namespace pagecache::detail
