#pragma once
// Part index of count of a map, for batch schedulers (a Kubernetes Indexed Job, a Slurm array): each part
// computes its share of the grid, `lienewton merge` joins the parts' outputs into the unsharded one.
namespace lienewton {

struct Shard {
  int index = 0;
  int count = 1;
};

}  // namespace lienewton
