// `npm run vendor`: copies uPlot from node_modules into web/vendor/ so that the service serves the page
// with no npm and no CDN at run time. The browser test checks that the copies are current.
import { copyFileSync, readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
export const VENDORED = [
  ['node_modules/uplot/dist/uPlot.esm.js', 'web/vendor/uPlot.esm.js'],
  ['node_modules/uplot/dist/uPlot.min.css', 'web/vendor/uPlot.min.css'],
  ['node_modules/uplot/LICENSE', 'web/vendor/uPlot.LICENSE'],
];

export function staleVendored() {
  return VENDORED.filter(([from, to]) => !readFileSync(join(root, from)).equals(readFileSync(join(root, to))))
    .map(([, to]) => to);
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  for (const [from, to] of VENDORED) {
    copyFileSync(join(root, from), join(root, to));
    console.log(`${from} -> ${to}`);
  }
}
