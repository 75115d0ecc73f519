// Google Benchmark targets for the pathing core on generated maps (no external data needed).
// For the MovingAI maps use `rts bench scen`.

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <vector>

#include "pathing/aa_star.h"
#include "pathing/cooperative_search.h"
#include "pathing/haa_star.h"
#include "pathing/jump_point_search.h"
#include "pathing/map_generator.h"
#include "pathing/random.h"
#include "pathing/terrain_costs.h"

namespace {

using namespace warpath::pathing;

GridMap benchmarkMap(int side) {
  RandomMapSpec spec;
  spec.width = side;
  spec.height = side;
  spec.seed = 2008;  // fixed: every run measures the same map
  spec.blockedPercent = 20;
  spec.maxPatch = 8;
  return generateRandomMap(spec);
}

// 64 fixed queries between cells the agent can stand on, at least `minDistance` apart
// (Manhattan).
std::vector<std::pair<Cell, Cell>> standableQueries(const AnnotatedGrid& grid, Agent agent,
                                                    int minDistance) {
  std::vector<std::pair<Cell, Cell>> queries;
  SplitMix64 rng(7);
  const int w = grid.map().width();
  const int h = grid.map().height();
  while (queries.size() < 64) {
    const Cell s{rng.between(0, w - 1), rng.between(0, h - 1)};
    const Cell g{rng.between(0, w - 1), rng.between(0, h - 1)};
    if (std::abs(s.x - g.x) + std::abs(s.y - g.y) < minDistance) continue;
    if (grid.canStand(agent, s) && grid.canStand(agent, g)) queries.push_back({s, g});
  }
  return queries;
}

// Times `find(start, goal, path)` over the queries, round and round.
template <class Find>
void timeQueries(benchmark::State& state, const std::vector<std::pair<Cell, Cell>>& queries,
                 const Find& find) {
  std::vector<Cell> path;
  std::size_t next = 0;
  for (auto _ : state) {
    const auto& [s, g] = queries[next++ % queries.size()];
    benchmark::DoNotOptimize(find(s, g, &path));
  }
}

const Capability kInfantry = Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Trees});

void BM_Clearance(benchmark::State& state) {
  const GridMap map = benchmarkMap(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(ClearanceField::compute(map, kInfantry));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(map.cellCount()));
}
BENCHMARK(BM_Clearance)->Arg(512)->Unit(benchmark::kMicrosecond);

void BM_AgentLayer(benchmark::State& state) {
  const GridMap map = benchmarkMap(512);
  const ClearanceField field = ClearanceField::compute(map, kInfantry);
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        AgentLayer::compute(map, field, {static_cast<int>(state.range(0)), kInfantry}));
  }
}
BENCHMARK(BM_AgentLayer)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond);

// Random queries between standable cells; reports expansions per second.
void BM_AnnotatedAStar(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const AnnotatedGrid grid(benchmarkMap(512));
  const Agent agent{size, kInfantry};
  const std::vector<std::pair<Cell, Cell>> queries = standableQueries(grid, agent, 0);
  AnnotatedAStar search(grid);
  std::vector<Cell> path;
  std::size_t next = 0;
  std::int64_t expanded = 0;
  for (auto _ : state) {
    const auto& [s, g] = queries[next++ % queries.size()];
    expanded += static_cast<std::int64_t>(search.findPath(agent, s, g, &path).metrics.expanded);
  }
  state.counters["expanded_per_s"] =
      benchmark::Counter(static_cast<double>(expanded), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AnnotatedAStar)->Arg(1)->Arg(3)->Unit(benchmark::kMicrosecond);

// The same queries by jump points: Args(size, precomputed). The layer's bit maps (and JPS+
// table) are built before timing.
void BM_JumpPointSearch(benchmark::State& state) {
  const AnnotatedGrid grid(benchmarkMap(512));
  const Agent agent{static_cast<int>(state.range(0)), kInfantry};
  JumpPointSearch search(grid,
                         state.range(1) != 0 ? JumpDistances::Precomputed : JumpDistances::Scanned);
  const std::vector<std::pair<Cell, Cell>> queries = standableQueries(grid, agent, 0);
  search.findPath(agent, queries[0].first, queries[0].second, nullptr);
  timeQueries(state, queries, [&](Cell s, Cell g, std::vector<Cell>* path) {
    return search.findPath(agent, s, g, path);
  });
}
BENCHMARK(BM_JumpPointSearch)
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({3, 0})
    ->Args({3, 1})
    ->Unit(benchmark::kMicrosecond);

// JPS+'s table for one layer of the 512x512 map, built at the layer's first query.
void BM_JumpTableBuild(benchmark::State& state) {
  const AnnotatedGrid grid(benchmarkMap(512));
  const Agent agent{1, kInfantry};
  for (auto _ : state) {
    JumpPointSearch search(grid, JumpDistances::Precomputed);
    benchmark::DoNotOptimize(search.jumpDistances(agent).data());
  }
}
BENCHMARK(BM_JumpTableBuild)->Unit(benchmark::kMillisecond);

// The same table repaired after a k x k obstacle goes down or is cleared (alternately, at a spot
// that moves every pair), sizes 1 and 3: Args(k, size). The grid's own repair is not timed.
void BM_JumpTableRepair(benchmark::State& state) {
  AnnotatedGrid grid(benchmarkMap(512));
  const int k = static_cast<int>(state.range(0));
  const Agent agent{static_cast<int>(state.range(1)), kInfantry};
  JumpPointSearch search(grid, JumpDistances::Precomputed);
  benchmark::DoNotOptimize(search.jumpDistances(agent).data());
  SplitMix64 rng(11);
  CellRect spot{0, 0, k, k};
  bool placed = false;
  for (auto _ : state) {
    state.PauseTiming();
    if (placed) {
      grid.clearObstacle(spot);
    } else {
      spot = {rng.between(0, 511 - k), rng.between(0, 511 - k), k, k};
      grid.placeObstacle(spot);
    }
    placed = !placed;
    state.ResumeTiming();
    benchmark::DoNotOptimize(search.jumpDistances(agent).data());
  }
  state.counters["repairs"] = static_cast<double>(search.tableCounts().repairs);
}
BENCHMARK(BM_JumpTableRepair)
    ->Args({1, 1})
    ->Args({16, 1})
    ->Args({16, 3})
    ->Args({64, 1})
    ->Unit(benchmark::kMicrosecond);

// The catalogue's capabilities (infantry, jeep and tank, amphibious), sizes 1-3.
AbstractionSpec catalogueSpec(int clusterSize, AbstractionQuality quality) {
  AbstractionSpec spec;
  spec.clusterSize = clusterSize;
  spec.maxAgentSize = 3;
  spec.capabilities = {kInfantry, Capability::of({Terrain::Ground}),
                       Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Water})};
  spec.quality = quality;
  return spec;
}

// Building the graph alone: the grid's clearance and agent layers are computed beforehand.
// Cluster size range(0), quality range(1), on `threads` (AbstractionSpec::threads).
void timeAbstractionBuild(benchmark::State& state, int threads) {
  const AnnotatedGrid grid(benchmarkMap(512));
  const auto quality = static_cast<AbstractionQuality>(state.range(1));
  AbstractionSpec spec = catalogueSpec(static_cast<int>(state.range(0)), quality);
  spec.threads = threads;
  ClusterAbstraction::build(grid, spec);  // warms the grid's caches
  for (auto _ : state) {
    benchmark::DoNotOptimize(ClusterAbstraction::build(grid, spec));
  }
}
void BM_AbstractionBuild(benchmark::State& state) {
  timeAbstractionBuild(state, 1);
}
// Threads range(2).
void BM_AbstractionBuildThreads(benchmark::State& state) {
  timeAbstractionBuild(state, static_cast<int>(state.range(2)));
}
BENCHMARK(BM_AbstractionBuild)
    ->Args({16, static_cast<int>(AbstractionQuality::High)})
    ->Args({16, static_cast<int>(AbstractionQuality::Low)})
    ->Unit(benchmark::kMillisecond);
// The same on 1, 2 and 4 threads, timed by the wall clock (CPU time counts one thread).
BENCHMARK(BM_AbstractionBuildThreads)
    ->ArgsProduct({{16},
                   {static_cast<int>(AbstractionQuality::High),
                    static_cast<int>(AbstractionQuality::Low)},
                   {1, 2, 4}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Random long queries (endpoints at least 256 cells apart) for infantry of sizes 1 and 3, by
// HAA* with `options`; what the planner builds per agent (insertion tables) is built before the
// timing.
void timeLongHaaQueries(benchmark::State& state, HaaOptions options) {
  const int size = static_cast<int>(state.range(0));
  const AnnotatedGrid grid(benchmarkMap(512));
  const ClusterAbstraction graph =
      ClusterAbstraction::build(grid, catalogueSpec(16, AbstractionQuality::High));
  const Agent agent{size, kInfantry};
  const std::vector<std::pair<Cell, Cell>> queries = standableQueries(grid, agent, 256);
  HierarchicalAStar search(graph, options);
  search.prepare(agent);
  timeQueries(state, queries, [&](Cell s, Cell g, std::vector<Cell>* path) {
    return search.findPath(agent, s, g, path);
  });
  if (options.insertion == InsertionMode::Tables)
    state.counters["table_bytes"] = static_cast<double>(search.insertionTableBytes());
}

void BM_HierarchicalAStar(benchmark::State& state) {
  timeLongHaaQueries(state, HaaOptions{});
}
BENCHMARK(BM_HierarchicalAStar)->Arg(1)->Arg(3)->Unit(benchmark::kMicrosecond);

// The same queries with insertion by tables (HaaOptions::insertion).
void BM_HaaInsertionTables(benchmark::State& state) {
  timeLongHaaQueries(state, HaaOptions{.insertion = InsertionMode::Tables});
}
BENCHMARK(BM_HaaInsertionTables)->Arg(1)->Arg(3)->Unit(benchmark::kMicrosecond);

// The same queries without cached paths (each intra-edge refined by a search inside its
// cluster) and short ones (endpoints 4-16 cells apart, many inside one cluster), with the grid
// searches by AA* (0) or JPS (1): HaaOptions::gridSearch.
void BM_HaaGridSearch(benchmark::State& state) {
  const bool uncached = state.range(0) == 0;
  const auto gridSearch = static_cast<GridSearch>(state.range(1));
  const AnnotatedGrid grid(benchmarkMap(512));
  AbstractionSpec spec = catalogueSpec(16, AbstractionQuality::High);
  spec.cachePaths = !uncached;
  const ClusterAbstraction graph = ClusterAbstraction::build(grid, spec);
  const Agent agent{1, kInfantry};
  std::vector<std::pair<Cell, Cell>> queries;
  if (uncached) {
    queries = standableQueries(grid, agent, 256);
  } else {
    const std::span<const std::uint32_t> component = grid.layer(agent).components();
    SplitMix64 rng(11);
    while (queries.size() < 64) {
      const Cell s{rng.between(0, 511), rng.between(0, 511)};
      const Cell g{s.x + rng.between(-12, 12), s.y + rng.between(-12, 12)};
      if (grid.map().contains(g) && grid.canStand(agent, s) && grid.canStand(agent, g) &&
          component[grid.map().indexOf(s)] == component[grid.map().indexOf(g)])
        queries.push_back({s, g});
    }
  }
  HierarchicalAStar search(graph, HaaOptions{.gridSearch = gridSearch});
  timeQueries(state, queries, [&](Cell s, Cell g, std::vector<Cell>* path) {
    return search.findPath(agent, s, g, path);
  });
}
BENCHMARK(BM_HaaGridSearch)
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMicrosecond);

// Sliced searches (issue 15): the same queries as above (infantry, size 1) run in slices of
// `batch` expansions (beginPath, updatePath until done, finalizePath), against one findPath
// each for batch 0: the cost of stopping and resuming.
template <class Search>
void timeSliced(benchmark::State& state, Search& search, Agent agent,
                const std::vector<std::pair<Cell, Cell>>& queries) {
  const auto batch = static_cast<std::uint64_t>(state.range(0));
  std::vector<Cell> path;
  std::size_t next = 0;
  std::int64_t updates = 0;
  for (auto _ : state) {
    const auto& [s, g] = queries[next++ % queries.size()];
    if (batch == 0) {
      benchmark::DoNotOptimize(search.findPath(agent, s, g, &path));
      continue;
    }
    for (PathStatus status = search.beginPath(agent, s, g); status == PathStatus::Pending;
         ++updates)
      status = search.updatePath(batch);
    benchmark::DoNotOptimize(search.finalizePath(&path));
  }
  state.counters["updates_per_query"] =
      benchmark::Counter(static_cast<double>(updates), benchmark::Counter::kAvgIterations);
}

void BM_SlicedAnnotatedAStar(benchmark::State& state) {
  const AnnotatedGrid grid(benchmarkMap(512));
  const Agent agent{1, kInfantry};
  AnnotatedAStar search(grid);
  timeSliced(state, search, agent, standableQueries(grid, agent, 0));
}
BENCHMARK(BM_SlicedAnnotatedAStar)->Arg(0)->Arg(256)->Unit(benchmark::kMicrosecond);

void BM_SlicedHierarchicalAStar(benchmark::State& state) {
  const AnnotatedGrid grid(benchmarkMap(512));
  const ClusterAbstraction graph =
      ClusterAbstraction::build(grid, catalogueSpec(16, AbstractionQuality::High));
  const Agent agent{1, kInfantry};
  HierarchicalAStar search(graph);
  timeSliced(state, search, agent, standableQueries(grid, agent, 256));
}
BENCHMARK(BM_SlicedHierarchicalAStar)->Arg(0)->Arg(256)->Unit(benchmark::kMicrosecond);

// The cooperative search's heuristic (issue 12): exact distances inside a corridor of half-width
// 4 (the default) around an infantry unit's HAA* path, as the path service builds one for each
// unit that needs windows. Paths of 150-250 cells, like stress_2000's crossings.
void BM_CorridorDistance(benchmark::State& state) {
  const AnnotatedGrid grid(benchmarkMap(512));
  const ClusterAbstraction graph =
      ClusterAbstraction::build(grid, catalogueSpec(16, AbstractionQuality::High));
  const Agent agent{1, kInfantry};
  HierarchicalAStar search(graph);
  std::vector<std::vector<Cell>> paths;
  for (const auto& [s, g] : standableQueries(grid, agent, 150)) {
    std::vector<Cell> path;
    if (search.findPath(agent, s, g, &path).found() && path.size() <= 250) paths.push_back(path);
  }
  std::size_t next = 0;
  for (auto _ : state) {
    const std::vector<Cell>& path = paths[next++ % paths.size()];
    CorridorDistance field(grid, agent, path, 4);
    benchmark::DoNotOptimize(field.distance(path.front()));  // runs the Dijkstra
    benchmark::DoNotOptimize(field.expanded());
  }
}
BENCHMARK(BM_CorridorDistance)->Unit(benchmark::kMicrosecond);

// Terrain costs (issue 13): the catalogue's infantry, 1 / (1.5, 0.8, 1.0) s per cell on ground,
// swamp and trees.
TerrainCosts infantryCosts() {
  TerrainCosts costs;
  costs.perCell[static_cast<std::size_t>(Terrain::Ground)] = 1.0 / 1.5;
  costs.perCell[static_cast<std::size_t>(Terrain::Swamp)] = 1.0 / 0.8;
  costs.perCell[static_cast<std::size_t>(Terrain::Trees)] = 1.0;
  return costs;
}

AbstractionSpec weightedSpec(int size, AbstractionQuality quality) {
  return weightedAbstractionSpec({size, kInfantry}, infantryCosts(), 16, quality);
}

// Weighted AA* on the long queries of BM_HierarchicalAStar: the baseline of the speed-up.
void BM_WeightedAnnotatedAStar(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const AnnotatedGrid grid(benchmarkMap(512));
  const Agent agent{size, kInfantry};
  const CostField costs(grid, agent, infantryCosts());
  const std::vector<std::pair<Cell, Cell>> queries = standableQueries(grid, agent, 256);
  AnnotatedAStar search(grid);
  timeQueries(state, queries, [&](Cell s, Cell g, std::vector<Cell>* path) {
    return search.findPath(agent, s, g, path, costs);
  });
}
BENCHMARK(BM_WeightedAnnotatedAStar)->Arg(1)->Arg(3)->Unit(benchmark::kMicrosecond);

// Weighted HAA* on the same queries, HQ (quality 0) and LQ (1); `error_pct` is the mean cost
// above weighted AA*'s optimum over the query set.
void BM_WeightedHierarchicalAStar(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const auto quality = static_cast<AbstractionQuality>(state.range(1));
  const AnnotatedGrid grid(benchmarkMap(512));
  const Agent agent{size, kInfantry};
  const ClusterAbstraction graph = ClusterAbstraction::build(grid, weightedSpec(size, quality));
  const std::vector<std::pair<Cell, Cell>> queries = standableQueries(grid, agent, 256);
  HierarchicalAStar search(graph);
  AnnotatedAStar reference(grid);
  double excess = 0.0;
  int found = 0;
  for (const auto& [s, g] : queries) {
    const PathResult optimum = reference.findPath(agent, s, g, nullptr, *graph.costs());
    const PathResult r = search.findPath(agent, s, g, nullptr);
    if (!optimum.found() || !r.found()) continue;
    excess += r.cost / optimum.cost - 1.0;
    ++found;
  }
  timeQueries(state, queries, [&](Cell s, Cell g, std::vector<Cell>* path) {
    return search.findPath(agent, s, g, path);
  });
  state.counters["error_pct"] = found > 0 ? 100.0 * excess / found : 0.0;
  state.counters["nodes"] = static_cast<double>(graph.stats().nodes);
}
BENCHMARK(BM_WeightedHierarchicalAStar)
    ->Args({1, static_cast<int>(AbstractionQuality::High)})
    ->Args({1, static_cast<int>(AbstractionQuality::Low)})
    ->Args({3, static_cast<int>(AbstractionQuality::High)})
    ->Unit(benchmark::kMicrosecond);

// Building one weighted graph (one agent kind; HQ).
void BM_WeightedAbstractionBuild(benchmark::State& state) {
  const AnnotatedGrid grid(benchmarkMap(512));
  const AbstractionSpec spec =
      weightedSpec(static_cast<int>(state.range(0)), AbstractionQuality::High);
  ClusterAbstraction::build(grid, spec);  // warms the grid's caches
  for (auto _ : state) {
    benchmark::DoNotOptimize(ClusterAbstraction::build(grid, spec));
  }
}
BENCHMARK(BM_WeightedAbstractionBuild)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond);

// Terrain that changes (issue 14): one change of a k×k square (range 0) on the 512² map, HQ (0)
// or LQ (1) graph of the catalogue (range 1), and what it costs to repair: the grid's caches
// (clearance, agent layers of sizes 1-3 of the three capabilities) and the graph. Iterations
// alternate placing an obstacle and clearing it at a spot that moves each pair, so the map
// returns to what it was. Compare with BM_AbstractionBuild (a whole build of the same graph).
// On `threads` (AbstractionSpec::threads).
void timeTerrainRepair(benchmark::State& state, int threads) {
  const int side = static_cast<int>(state.range(0));
  const auto quality = static_cast<AbstractionQuality>(state.range(1));
  AnnotatedGrid grid(benchmarkMap(512));
  AbstractionSpec spec = catalogueSpec(16, quality);
  spec.threads = threads;
  grid.setUpdateThreads(threads);
  ClusterAbstraction graph = ClusterAbstraction::build(grid, spec);
  SplitMix64 rng(14);
  CellRect area{};
  bool placed = false;
  double clusters = 0;
  for (auto _ : state) {
    if (!placed) area = {rng.between(0, 511 - side), rng.between(0, 511 - side), side, side};
    const TerrainChange change = placed ? grid.clearObstacle(area) : grid.placeObstacle(area);
    placed = !placed;
    clusters += graph.repair(change).clusters;
  }
  state.counters["nodes"] = static_cast<double>(graph.stats().nodes);
  state.counters["clusters"] = benchmark::Counter(clusters, benchmark::Counter::kAvgIterations);
}
void BM_TerrainRepair(benchmark::State& state) {
  timeTerrainRepair(state, 1);
}
// Threads range(2).
void BM_TerrainRepairThreads(benchmark::State& state) {
  timeTerrainRepair(state, static_cast<int>(state.range(2)));
}
BENCHMARK(BM_TerrainRepair)
    ->ArgsProduct({{1, 4, 16, 64, 128},
                   {static_cast<int>(AbstractionQuality::High),
                    static_cast<int>(AbstractionQuality::Low)}})
    ->Unit(benchmark::kMicrosecond);
// The 16×16 and 64×64 changes with the clusters searched on 1, 2 and 4 threads, by the wall
// clock.
BENCHMARK(BM_TerrainRepairThreads)
    ->ArgsProduct({{16, 64},
                   {static_cast<int>(AbstractionQuality::High),
                    static_cast<int>(AbstractionQuality::Low)},
                   {1, 2, 4}})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

// The same for one weighted graph (terrain costs: one graph per unit kind), infantry costs,
// size range(1), HQ.
void BM_WeightedTerrainRepair(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const int size = static_cast<int>(state.range(1));
  AnnotatedGrid grid(benchmarkMap(512));
  ClusterAbstraction graph =
      ClusterAbstraction::build(grid, weightedSpec(size, AbstractionQuality::High));
  SplitMix64 rng(14);
  CellRect area{};
  bool placed = false;
  for (auto _ : state) {
    if (!placed) area = {rng.between(0, 511 - side), rng.between(0, 511 - side), side, side};
    const TerrainChange change = placed ? grid.clearObstacle(area) : grid.placeObstacle(area);
    placed = !placed;
    benchmark::DoNotOptimize(graph.repair(change));
  }
}
BENCHMARK(BM_WeightedTerrainRepair)->Args({16, 1})->Args({16, 3})->Unit(benchmark::kMicrosecond);

// The grid's share of BM_TerrainRepair: clearance and agent layers alone.
void BM_GridRepair(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  AnnotatedGrid grid(benchmarkMap(512));
  (void)ClusterAbstraction::build(grid, catalogueSpec(16, AbstractionQuality::High));
  SplitMix64 rng(14);
  CellRect area{};
  bool placed = false;
  for (auto _ : state) {
    if (!placed) area = {rng.between(0, 511 - side), rng.between(0, 511 - side), side, side};
    benchmark::DoNotOptimize(placed ? grid.clearObstacle(area) : grid.placeObstacle(area));
    placed = !placed;
  }
}
BENCHMARK(BM_GridRepair)->Arg(16)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
