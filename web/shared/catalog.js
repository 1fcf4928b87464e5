// The server's vocabulary, loaded once for every panel: the "x-lienewton" extension of /openapi.json holds a
// label, a short label, a description and for some an explanation for each value of the API's enums (problem,
// method, differential, integrator, linear_solver, globalization, stopping, predictor, branch, found_by, path_point, status,
// heatmap_metric), the status colours, the heatmap renderer's colours, and where each group draws bodies (groups).
// Nothing here is copied from the server, so a new method or status shows up with its own words.
const response = await fetch('/openapi.json');
if (!response.ok) throw new Error(`/openapi.json answered HTTP ${response.status}`);
const openapi = await response.json();
export const catalog = openapi['x-lienewton'];
// The request schemas (SolveRequest, ...): each field's type, bounds, default and description.
export const schemas = openapi.components.schemas;

// The entries of one enum, in the server's order: {value, label, short, description, explanation?, ...}.
export function entries(name) {
  const list = catalog.enums[name];
  if (!list) throw new Error(`/openapi.json publishes no labels for ${name}`);
  return list;
}

// [value, text] pairs for selects, checkbox lists and column heads; key picks 'label' or 'short'.
export function choices(name, key = 'label') {
  return entries(name).map((e) => [e.value, e[key]]);
}

// One value's entry; a value the server does not list reads as itself.
export function entry(name, value) {
  return entries(name).find((e) => e.value === value) ?? { value, label: value, short: value, description: '' };
}
