#include "kaboum/geometry/decomposition_merge.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <deque>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <span>
#include <unordered_map>
#include <utility>

namespace kaboum::geometry {
namespace {

// The triangles of the merged hull of pieces a and b that bridge them: those whose corners are not
// all vertices of one part (a triangle spanned by one part's vertices lies in that part's hull).
TriangleMesh bridgeTriangles(const Cell& merged, const Cell& a, const Cell& b) {
  const auto sorted = [](const Cell& c) {
    std::vector<Vec3> points = c.hull.mesh.vertices;
    std::sort(points.begin(), points.end(), lexicographicLess);
    return points;
  };
  const std::vector<Vec3> first = sorted(a), second = sorted(b);
  const auto allIn = [&](const std::vector<Vec3>& part, const Triangle& t) {
    return std::all_of(t.begin(), t.end(), [&](std::uint32_t v) {
      return std::binary_search(part.begin(), part.end(), merged.hull.mesh.vertices[v],
                                lexicographicLess);
    });
  };
  TriangleMesh bridge;
  bridge.vertices = merged.hull.mesh.vertices;
  for (const Triangle& t : merged.hull.mesh.triangles) {
    if (!allIn(first, t) && !allIn(second, t)) bridge.triangles.push_back(t);
  }
  return bridge;
}

// The search of mergeLeaves.
class MergeSearch {
 public:
  MergeSearch(std::vector<Cell>& leaves, const DecompositionContext& context, double tolerance,
              std::uint64_t& measured)
      : context_(context), tolerance_(tolerance), measured_(measured) {
    for (std::uint32_t i = 0; i < leaves.size(); ++i) {
      nodes_.push_back(Node{std::move(leaves[i]), {i}, kNone, kNone, 0, true, true, true, nullptr});
      byLeaves_.emplace(std::vector<std::uint32_t>{i}, i);
      alive_.push_back(i);
    }
  }

  // Merges as described above; returns the pieces left.
  std::vector<Piece> run(std::size_t maxPieces, double budget) {
    constexpr double kNoBar = std::numeric_limits<double>::infinity();
    while (alive_.size() > 1) {
      const std::size_t forcedLeft = alive_.size() > maxPieces ? alive_.size() - maxPieces : 0;
      std::optional<Choice> chosen = cheapest(alive_, {}, kNoBar);
      if (!chosen) break;
      if (forcedLeft == 0 && concavity(chosen->node) > budget) break;
      if (forcedLeft > 1 && forcedLeft <= kLookaheadWindow) chosen = lookahead(*chosen, maxPieces);
      apply(alive_, *chosen);
      keepHull(nodes_[chosen->node].cell, context_.snap);
    }
    std::vector<Piece> pieces;
    for (const std::uint32_t id : alive_) {
      Piece piece;
      for (const std::uint32_t leaf : nodes_[id].leaves) {
        // The leaves of a merged piece are needed only in its region; a leaf piece is its own.
        if (leaf == id) {
          piece.region.push_back(nodes_[leaf].cell);
        } else {
          piece.region.push_back(std::move(nodes_[leaf].cell));
        }
      }
      piece.cell = std::move(nodes_[id].cell);
      pieces.push_back(std::move(piece));
    }
    return pieces;
  }

 private:
  static constexpr std::size_t kLookaheadWindow = 6;
  static constexpr std::size_t kLookaheadWidth = 12;
  static constexpr std::uint32_t kNone = 0xffffffffu;

  // A piece: a leaf, or the hull of two pieces (`first`, `second`) covering `leaves` (sorted).
  struct Node {
    Cell cell;
    std::vector<std::uint32_t> leaves;
    std::uint32_t first, second;
    std::uint64_t salt;                            // of the bridge samples
    bool built;                                    // the hull is built
    bool usable;                                   // false when the hull has no volume
    bool exact;                                    // cell.concavity is measured, else a lower bound
    std::unique_ptr<MergedConcavity> measurement;  // while built and not exact
  };
  // A merge: the positions of its two pieces in a list of pieces and the merged piece.
  struct Choice {
    std::size_t i, j;
    std::uint32_t node;
  };
  // The largest concavity at the piece limit when greedy merging goes on from a state, or a
  // lower bound of it.
  struct Outcome {
    double concavity;
    bool exact;
  };

  [[nodiscard]] double concavity(std::uint32_t node) const { return nodes_[node].cell.concavity; }

  // The merged piece of nodes a and b (its hull not built yet), or kNone when they do not touch.
  std::uint32_t pairNode(std::uint32_t a, std::uint32_t b) {
    const std::uint64_t key = std::uint64_t{std::min(a, b)} << 32 | std::max(a, b);
    const auto [entry, inserted] = pairs_.try_emplace(key, kNone);
    if (!inserted) return entry->second;
    if (!boxesTouch(nodes_[a].cell, nodes_[b].cell, tolerance_)) return kNone;
    std::vector<std::uint32_t> leaves;
    std::merge(nodes_[a].leaves.begin(), nodes_[a].leaves.end(), nodes_[b].leaves.begin(),
               nodes_[b].leaves.end(), std::back_inserter(leaves));
    if (const auto known = byLeaves_.find(leaves); known != byLeaves_.end()) {
      return entry->second = known->second;
    }
    const auto id = static_cast<std::uint32_t>(nodes_.size());
    Node node{Cell{}, leaves, a, b, measured_++, false, true, false, nullptr};
    node.cell.concavity = std::max(concavity(a), concavity(b));  // a lower bound
    nodes_.push_back(std::move(node));
    byLeaves_.emplace(std::move(leaves), id);
    return entry->second = id;
  }

  // Measures the merged piece until its concavity passes `limit`.
  void measure(Node& node, double limit) {
    const Cell& first = nodes_[node.first].cell;
    const Cell& second = nodes_[node.second].cell;
    if (!node.built) {
      node.built = true;
      std::optional<Cell> merged = mergedCell(first, second, context_.snap);
      if (!merged) {
        node.usable = false;
        return;
      }
      merged->concavity = node.cell.concavity;
      node.cell = std::move(*merged);
      node.measurement =
          std::make_unique<MergedConcavity>(node.cell, first, second, context_, node.salt);
    }
    node.exact = node.measurement->measure(
        node.cell, context_.solid, std::nextafter(limit, std::numeric_limits<double>::infinity()));
    if (node.exact) node.measurement.reset();
  }

  // The pair of `alive` whose merged piece has the smallest concavity (the first of equals in
  // pair order), skipping merged pieces in `excluded`; nothing when no pair can merge. When that
  // concavity is at least `bar`, a pair whose concavity (or lower bound) is at least `bar`.
  std::optional<Choice> cheapest(const std::vector<std::uint32_t>& alive,
                                 std::span<const Choice> excluded, double bar) {
    while (true) {
      std::optional<Choice> best, bound;
      for (std::size_t i = 0; i < alive.size(); ++i) {
        for (std::size_t j = i + 1; j < alive.size(); ++j) {
          const std::uint32_t id = pairNode(alive[i], alive[j]);
          if (id == kNone || !nodes_[id].usable ||
              std::any_of(excluded.begin(), excluded.end(),
                          [&](const Choice& c) { return c.node == id; })) {
            continue;
          }
          std::optional<Choice>& current = nodes_[id].exact ? best : bound;
          if (!current || concavity(id) < concavity(current->node)) current = Choice{i, j, id};
        }
      }
      const double limit =
          std::min(best ? concavity(best->node) : std::numeric_limits<double>::infinity(), bar);
      if (!bound || concavity(bound->node) > limit) return best ? best : bound;
      measure(nodes_[bound->node], limit);
    }
  }

  static void apply(std::vector<std::uint32_t>& alive, const Choice& choice) {
    alive[choice.i] = choice.node;
    alive.erase(alive.begin() + static_cast<std::ptrdiff_t>(choice.j));
  }

  // The largest concavity at the piece limit after `choice` and greedy merges, or infinity when
  // it is at least `bar` (no better than a score already found).
  double completion(Choice choice, std::size_t maxPieces, double bar) {
    constexpr double kAbove = std::numeric_limits<double>::infinity();
    std::vector<std::uint32_t> alive = alive_;
    std::vector<std::vector<std::uint32_t>> path;  // the states passed
    std::optional<double> result;
    while (concavity(choice.node) < bar) {
      apply(alive, choice);
      std::vector<std::uint32_t> state = alive;
      std::sort(state.begin(), state.end());
      if (const auto known = outcomes_.find(state); known != outcomes_.end()) {
        if (known->second.exact) result = known->second.concavity;
        if (result || known->second.concavity >= bar) break;
      }
      path.push_back(std::move(state));
      const std::optional<Choice> next =
          alive.size() > maxPieces ? cheapest(alive, {}, bar) : std::nullopt;
      if (!next) {
        result = 0.0;
        for (const std::uint32_t id : alive) *result = std::max(*result, concavity(id));
        break;
      }
      choice = *next;
    }
    for (auto& state : path) {
      Outcome& outcome = outcomes_.try_emplace(std::move(state), Outcome{0.0, false}).first->second;
      if (result) {
        outcome = {*result, true};
      } else if (!outcome.exact) {
        outcome.concavity = std::max(outcome.concavity, bar);
      }
    }
    return result && *result < bar ? *result : kAbove;
  }

  // Among the kLookaheadWidth cheapest pairs (`greedy` first), the one with the best completion.
  Choice lookahead(const Choice& greedy, std::size_t maxPieces) {
    std::vector<Choice> candidates{greedy};
    while (candidates.size() < kLookaheadWidth) {
      const std::optional<Choice> next =
          cheapest(alive_, candidates, std::numeric_limits<double>::infinity());
      if (!next) break;
      candidates.push_back(*next);
    }
    Choice best = greedy;
    double bestScore = completion(greedy, maxPieces, std::numeric_limits<double>::infinity());
    for (std::size_t k = 1; k < candidates.size(); ++k) {
      const double score = completion(candidates[k], maxPieces, bestScore);
      if (score < bestScore) {
        bestScore = score;
        best = candidates[k];
      }
    }
    return best;
  }

  const DecompositionContext& context_;
  double tolerance_;
  std::uint64_t& measured_;
  std::deque<Node> nodes_;  // stable references while new pieces are added
  std::map<std::vector<std::uint32_t>, std::uint32_t> byLeaves_;
  std::unordered_map<std::uint64_t, std::uint32_t> pairs_;  // (smaller, larger id) -> merged
  std::map<std::vector<std::uint32_t>, Outcome> outcomes_;  // by a state's sorted pieces
  std::vector<std::uint32_t> alive_;                        // the current pieces, in leaf order
};

}  // namespace

bool boxesTouch(const Cell& a, const Cell& b, double tolerance) {
  const auto box = [](const Cell& c) {
    Eigen::AlignedBox3d result;
    for (const Vec3& v : c.hull.mesh.vertices) result.extend(v);
    return result;
  };
  Eigen::AlignedBox3d first = box(a);
  first.extend(first.min() - Vec3::Constant(tolerance))
      .extend(first.max() + Vec3::Constant(tolerance));
  return first.intersects(box(b));
}

std::optional<Cell> mergedCell(const Cell& a, const Cell& b, double snap) {
  Cell merged;
  merged.points = a.hull.mesh.vertices;
  merged.points.insert(merged.points.end(), b.hull.mesh.vertices.begin(),
                       b.hull.mesh.vertices.end());
  sortPoints(merged.points);
  if (!buildCandidateHull(merged, snap)) return std::nullopt;
  return merged;
}

MergedConcavity::MergedConcavity(const Cell& merged, const Cell& a, const Cell& b,
                                 const DecompositionContext& context, std::uint64_t salt)
    : bridge_(bridgeTriangles(merged, a, b)),
      samples_(bridge_, context.bridgeSamples, sampleSeed(context, salt)) {
  farthest_.distance = std::max(a.concavity, b.concavity);
}

bool MergedConcavity::measure(Cell& merged, const Solid& solid, double stopAt) {
  solid.largestDistance(samples_, stopAt, farthest_);
  merged.concavity = farthest_.distance;
  merged.worstPoint = farthest_.where;
  return farthest_.complete;
}

std::vector<Piece> mergeLeaves(std::vector<Cell> leaves, std::size_t maxPieces, double budget,
                               const DecompositionContext& context, double touchTolerance,
                               std::uint64_t& measured) {
  return MergeSearch(leaves, context, touchTolerance, measured).run(maxPieces, budget);
}

}  // namespace kaboum::geometry
