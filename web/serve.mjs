// A static file server for the demo (the page loads ES modules and a .wasm, which browsers do not
// load from file://): node web/serve.mjs [DIR] [PORT], or startServer() from a test.
import { createReadStream, statSync } from 'node:fs';
import { createServer } from 'node:http';
import { extname, join, normalize, resolve } from 'node:path';

const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css',
                '.json': 'application/json', '.wasm': 'application/wasm', '.png': 'image/png' };

export function startServer(root, port = 0) {
  const base = resolve(root);
  const server = createServer((request, response) => {
    const path = normalize(decodeURIComponent(new URL(request.url, 'http://localhost').pathname));
    const file = join(base, path);
    let stat = null;
    try { stat = statSync(file); } catch { stat = null; }
    if (!file.startsWith(base) || !stat || !stat.isFile()) {
      response.writeHead(404).end('not found');
      return;
    }
    response.writeHead(200, { 'Content-Type': types[extname(file)] ?? 'application/octet-stream' });
    createReadStream(file).pipe(response);
  });
  return new Promise((done) => server.listen(port, '127.0.0.1', () => done(server)));
}

if (import.meta.url === `file://${process.argv[1]}`) {
  const server = await startServer(process.argv[2] ?? 'build/web', Number(process.argv[3] ?? 8000));
  console.log(`serving on http://127.0.0.1:${server.address().port}/demo/`);
}
