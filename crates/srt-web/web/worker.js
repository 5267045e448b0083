// The exact CPU tracer (srt-trace, compiled to WebAssembly) off the page's main thread: it
// renders what the page asks and sends the RGBA bytes back, or measures what a picture costs.
import init, { CpuPage } from './srt_web.js';

const ready = init().then(() => new CpuPage());

self.onmessage = async (event) => {
  const message = event.data;
  const page = await ready;
  try {
    if (message.kind === 'model') {
      const warnings = page.load_model(message.name, message.bytes);
      self.postMessage({ id: message.id, warnings });
    } else if (message.kind === 'info') {
      page.set_query(message.query);
      self.postMessage({ id: message.id, info: page.info() });
    } else if (message.kind === 'measure') {
      page.set_query(message.query);
      self.postMessage({ id: message.id, seconds: page.measure(message.width, message.height) });
    } else if (message.kind === 'render') {
      page.set_query(message.query);
      const pixels = page.render(message.width, message.height);
      self.postMessage({ id: message.id, pixels }, [pixels.buffer]);
    }
  } catch (error) {
    self.postMessage({ id: message.id, error: String(error && error.message !== undefined ? error.message : error) });
  }
};
