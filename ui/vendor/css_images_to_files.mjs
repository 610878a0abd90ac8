// Swagger UI's style sheet with its images as files of their own, so that /docs keeps the pages'
// Content-Security-Policy `default-src 'self'` (which refuses data: URLs, CSP Level 3 §6.1.1):
//
//   node css_images_to_files.mjs IN.css OUT_DIR
//
// writes OUT_DIR/swagger-ui.css, where every url("data:image/svg+xml;charset=utf-8,<svg…>") is
// replaced by url("/ui/swagger-ui-image-N.svg"), N counting the distinct images in order of first
// use, and OUT_DIR/swagger-ui-image-N.svg, the image: the CSS string's escapes undone (CSS Syntax
// Level 3 §4.3.7), then the URL's percent-encoding (RFC 3986 §2.1; data: URLs, RFC 2397). The base64 raster images of tachyons' .debug-grid* classes, which the
// Swagger UI bundle never sets, become `none`. Any other data: URL is an error, so that a new
// version's images cannot slip past the policy unnoticed.
import fs from 'node:fs';
import path from 'node:path';

const [input, out] = process.argv.slice(2);
if (!input || !out) {
  console.error('usage: node css_images_to_files.mjs IN.css OUT_DIR');
  process.exit(2);
}
const css = fs.readFileSync(input, 'utf8');
const images = new Map();  // decoded SVG text -> file name
const svg = /url\("data:image\/svg\+xml;charset=utf-8,((?:[^"\\]|\\[^])*)"\)/g;
const raster = /url\(data:image\/(?:png|jpeg);base64,[A-Za-z0-9+/=]*\)/g;
// An escape is a backslash and either one to six hex digits (a code point, one white space after
// it belonging to the escape) or any other character (itself); a backslash before a newline is
// a line continuation.
const unescape = (s) =>
  s.replace(/\\(?:([0-9a-fA-F]{1,6})[ \t\n]?|\n|([^]))/g,
            (_, hex, other) => (hex ? String.fromCodePoint(parseInt(hex, 16)) : other ?? ''));
let rewritten = css.replace(svg, (_, escaped) => {
  const text = decodeURIComponent(unescape(escaped));
  if (!images.has(text)) images.set(text, `swagger-ui-image-${images.size + 1}.svg`);
  return `url("/ui/${images.get(text)}")`;
});
rewritten = rewritten.replace(raster, 'none');
const left = rewritten.match(/data:[^")]{0,60}/);
if (left) {
  console.error(`${input}: a data: URL this script does not handle: ${left[0]}`);
  process.exit(1);
}
fs.mkdirSync(out, {recursive: true});
for (const name of fs.readdirSync(out)) if (name.startsWith('swagger-ui')) fs.rmSync(path.join(out, name));
fs.writeFileSync(path.join(out, 'swagger-ui.css'), rewritten);
for (const [text, name] of images) fs.writeFileSync(path.join(out, name), text);
console.log(`${images.size} images`);
