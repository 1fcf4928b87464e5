#include "server/cli/paper_figures.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

namespace lienewton {
namespace {

using Grid = std::map<std::pair<int, double>, const SweepCell*>;

std::string cell_text(const SweepCell* c, bool rate) {
  if (!c) return " ";
  if (c->status != Status::converged) return std::string(1, status_code(c->status));
  if (!rate) return std::to_string(c->iterations);
  if (!c->rate) return "–";
  char buf[16];
  std::snprintf(buf, sizeof buf, "%.1f", *c->rate);
  return buf;
}

void table(std::ostringstream& out, const Grid& grid, const std::set<int>& ns, const std::set<double>& hs,
           bool rate) {
  out << "| N \\ log2 h |";
  for (double h : hs) out << ' ' << std::lround(std::log2(h)) << " |";
  out << "\n|---|";
  for (std::size_t i = 0; i < hs.size(); ++i) out << "---|";
  out << '\n';
  for (int n : ns) {
    out << "| " << n << " |";
    for (double h : hs) {
      const auto it = grid.find({n, h});
      out << ' ' << cell_text(it == grid.end() ? nullptr : it->second, rate) << " |";
    }
    out << '\n';
  }
}

}  // namespace

char status_code(Status status) {
  switch (status) {
    case Status::converged: return 'C';
    case Status::max_iterations: return 'M';
    case Status::diverged: return 'D';
    case Status::non_finite: return 'F';
    case Status::left_log_domain: return 'L';
    case Status::singular_differential: return 'X';
    case Status::stagnated: return 'S';
    case Status::off_branch: return 'B';
    case Status::local_minimum: return 'P';
    case Status::no_descent: return 'N';
    case Status::fold: return 'T';
    case Status::cancelled: return '-';
    case Status::min_step: return 'H';
    case Status::max_steps: return 'K';
  }
  return '?';
}

std::string figure_tables(const SweepResult& sweep, ProblemKind problem, Differential differential) {
  std::ostringstream out;
  std::map<Method, Grid> grids;
  std::set<int> ns;
  std::set<double> hs;
  for (const auto& c : sweep.cells) {
    grids[c.method][{c.n, c.h}] = &c;
    ns.insert(c.n);
    hs.insert(c.h);
  }
  for (const auto& [method, grid] : grids) {
    int converged = 0;
    for (const auto& [key, cell] : grid) converged += cell->status == Status::converged;
    out << "### " << to_string(problem) << ", " << to_string(method) << " (" << to_string(differential)
        << "): " << converged << " of " << grid.size() << " cells converged\n\nIterations to ||f|| <= tol:\n\n";
    table(out, grid, ns, hs, false);
    out << "\nRate r:\n\n";
    table(out, grid, ns, hs, true);
    out << '\n';
  }
  out << "Codes: M max_iterations, D diverged, F non_finite, L left_log_domain, X singular_differential, "
         "S stagnated, B off_branch, P local_minimum, N no_descent.\n\n";
  return out.str();
}

}  // namespace lienewton
