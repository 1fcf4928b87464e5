// A tiny element builder: el('p', { class: 'x' }, 'text', child). No framework needed for a few forms.
export function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, v] of Object.entries(attrs)) {
    if (v === false || v === null || v === undefined) continue;
    if (key === 'class') node.className = v;
    else if (key === 'dataset') Object.assign(node.dataset, v);
    else if (key === 'style') setStyle(node, v);
    else if (key.startsWith('on')) node.addEventListener(key.slice(2), v);
    else node.setAttribute(key, v === true ? '' : v);
  }
  node.append(...children.flat().filter((c) => c !== null && c !== undefined && c !== false));
  return node;
}

// 'name: value; ...' one property at a time through the CSSOM: the Content-Security-Policy (style-src 'self')
// refuses style attributes, and with them setAttribute('style') and style.cssText.
function setStyle(node, text) {
  for (const declaration of text.split(';')) {
    const colon = declaration.indexOf(':');
    if (colon > 0) node.style.setProperty(declaration.slice(0, colon).trim(), declaration.slice(colon + 1).trim());
  }
}

let counter = 0;
export const uid = (prefix) => `${prefix}-${++counter}`;
