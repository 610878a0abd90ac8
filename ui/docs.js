// The API reference (GET /docs): Swagger UI (npm's swagger-ui-dist, embedded at build time as
// /ui/swagger-ui-bundle.js) rendering the server's own /openapi.yaml, with "Try it out" sending
// requests to this origin (openapi.yaml's server is "/"). No validator badge: that would ask
// another origin, which the Content-Security-Policy refuses.
(function () {
  'use strict';

  function start() {
    const ui = SwaggerUIBundle({
      url: '/openapi.yaml',
      dom_id: '#docs',
      deepLinking: true,
      validatorUrl: null,
      displayRequestDuration: true,
      onComplete() {
        // Swagger UI reports a spec it could not fetch or parse as errors of its own.
        const errors = ui.errSelectors.allErrors();
        document.body.dataset.state = errors.size === 0 && ui.specSelectors.specJson().has('paths') ? 'ready' : 'error';
      },
    });
    window.footpointDocs = {ui};
  }

  window.addEventListener('DOMContentLoaded', start);
})();
