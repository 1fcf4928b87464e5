// "What is this?" for the choices a paper reader meets in the forms: each problem's g, each method, integrator
// and differential, with the equation numbers of Owren & Welfert (BIT 2000). The texts are the server
// catalog's explanations (its vocabulary, core/vocabulary.cpp); a value without one shows its one-line
// description.
import { catalog, entries, entry } from './catalog.js';
import { el } from './dom.js';

export function explanation(name, value) {
  const e = entry(name, value);
  return e.explanation ?? e.description;
}

// The enums whose selects get a disclosure: those with an explanation for some value.
export const EXPLAINED = Object.keys(catalog.enums).filter((name) => entries(name).some((e) => e.explanation));

// A disclosure under a select that explains its current value, kept in step with the select.
export function explainer(select) {
  const text = el('p', { class: 'about-text' });
  const box = el('details', { class: 'about', dataset: { about: select.name } },
    el('summary', {}, 'What is this?'), text);
  const sync = () => { text.textContent = explanation(select.name, select.value); };
  select.addEventListener('change', sync);
  select.addEventListener('input', sync);
  sync();
  return box;
}

// One disclosure for a tick table or checkbox list: every value of the named enums with its explanation.
export function explainerList(names) {
  return el('details', { class: 'about', dataset: { about: names.join(' ') } },
    el('summary', {}, 'What do these mean?'),
    el('dl', { class: 'about-text' }, names.flatMap((name) => entries(name).flatMap((e) => [
      el('dt', {}, e.label), el('dd', { dataset: { value: e.value } }, explanation(name, e.value))]))));
}
