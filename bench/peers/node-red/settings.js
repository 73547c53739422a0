// Node-RED's settings for the benchmark's peer row (bench/benchlib/node_red.py): headless, no
// editor, no admin API, no HTTP nodes, nothing written but the user directory the harness gives
// it, warnings only. The flow's ports come from the environment (flow.json's ${...} properties).
module.exports = {
    uiHost: "127.0.0.1",
    uiPort: Number(process.env.EIP2MQTT_PEER_UI_PORT || 0),
    httpAdminRoot: false,
    httpNodeRoot: false,
    credentialSecret: false,
    flowFilePretty: false,
    logging: { console: { level: "warn", metrics: false, audit: false } },
    diagnostics: { enabled: false, ui: false },
    runtimeState: { enabled: false, ui: false },
    telemetry: { enabled: false, updateNotification: false },
    externalModules: { autoInstall: false, palette: { allowInstall: false }, modules: { allowInstall: false } },
    functionExternalModules: false,
    functionGlobalContext: {},
    exportGlobalContextKeys: false,
    contextStorage: { default: { module: "memory" } },
};
