// An OPC UA client written with node-opcua (by others), for the server's tests: every result
// is one line on stdout that starts with "@@ " and holds JSON; node-opcua's own notes are other
// lines. Usage:
//   node client.js '{"url": ..., "action": "read" | "events" | "walk", ...options}'
// Options: security "none" | "sign_encrypt" (with cert, key: a client certificate in DER and its
// key in PEM), user and password (anonymous without), pki (a folder for node-opcua's own
// certificate store), refresh (events: call ConditionRefresh once subscribed), seconds (events:
// how long to listen).
"use strict";

const fs = require("fs");
const path = require("path");
const opcua = require("node-opcua-client");
const { OPCUACertificateManager } = require("node-opcua-certificate-manager");

const DI = "http://opcfoundation.org/UA/DI/";
const MACHINERY = "http://opcfoundation.org/UA/Machinery/";
const MT = "http://opcfoundation.org/UA/MachineTool/";

function say(obj) {
  // written at once: a pipe's asynchronous write is lost when process.exit follows it
  fs.writeSync(1, "@@ " + JSON.stringify(obj) + "\n");
}

function plain(value) {
  if (value === null || value === undefined) return null;
  if (typeof value === "bigint") return Number(value);
  if (Array.isArray(value)) return value.map(plain);
  if (value instanceof Date) return value.toISOString();
  if (Buffer.isBuffer(value)) return value.toString("hex");
  if (typeof value === "object") {
    if (typeof value.toString === "function" && value.constructor && value.constructor.name === "NodeId") {
      return value.toString();
    }
    if ("text" in value && "locale" in value) return value.text;
    if ("name" in value && "value" in value && Object.keys(value).length <= 3) return value.name;
    const out = {};
    for (const key of Object.keys(value)) {
      if (!key.startsWith("_")) out[key] = plain(value[key]);
    }
    return out;
  }
  return value;
}

async function connect(opts) {
  const secure = opts.security === "sign_encrypt";
  const manager = new OPCUACertificateManager({
    rootFolder: path.join(opts.pki, "pki"),
    automaticallyAcceptUnknownCertificate: true,
  });
  await manager.initialize();
  const client = opcua.OPCUAClient.create({
    applicationName: "node-opcua test client",
    applicationUri: "urn:test:client",
    securityMode: secure ? opcua.MessageSecurityMode.SignAndEncrypt : opcua.MessageSecurityMode.None,
    securityPolicy: secure ? opcua.SecurityPolicy.Basic256Sha256 : opcua.SecurityPolicy.None,
    certificateFile: opts.cert_pem,
    privateKeyFile: opts.key,
    clientCertificateManager: manager,
    endpointMustExist: false,
    connectionStrategy: { maxRetry: 0, initialDelay: 100 },
    requestedSessionTimeout: 20000,
  });
  await client.connect(opts.url);
  const identity = opts.user
    ? { type: opcua.UserTokenType.UserName, userName: opts.user, password: opts.password }
    : { type: opcua.UserTokenType.Anonymous };
  let session;
  try {
    session = await client.createSession(identity);
  } catch (err) {
    await client.disconnect();
    throw err;
  }
  return { client, session };
}

async function namespaces(session) {
  const array = (await session.readNamespaceArray());
  return { di: array.indexOf(DI), machinery: array.indexOf(MACHINERY), mt: array.indexOf(MT) };
}

async function machineNode(session, ns) {
  const result = await session.browse(`ns=${ns.machinery};i=1001`);
  if (!result.references || result.references.length === 0) throw new Error("the Machines folder is empty");
  return result.references[0].nodeId.toString();
}

async function read(opts) {
  const { client, session } = await connect(opts);
  try {
    const ns = await namespaces(session);
    const machine = await machineNode(session, ns);
    const paths = await session.translateBrowsePath(
      opcua.makeBrowsePath(machine, `/${ns.di}:Identification/${ns.di}:SerialNumber`));
    const serial = await session.read({ nodeId: paths.targets[0].targetId });
    say({ ok: true, serial: serial.value.value });
  } finally {
    await session.close();
    await client.disconnect();
  }
}

const EVENT_FIELDS = [
  "EventId", "EventType", "SourceName", "Message", "Severity", "Retain", "ConditionClassId",
  "ConditionClassName", "ConditionName", "BranchId", "EnabledState.Id", "Quality", "LastSeverity",
  "Comment", "ClientUserId", "ActiveState.Id", "AckedState.Id", "ErrorCode",
];

async function events(opts) {
  const { client, session } = await connect(opts);
  try {
    const subscription = await session.createSubscription2({
      requestedPublishingInterval: 50, requestedLifetimeCount: 1000, requestedMaxKeepAliveCount: 20,
      maxNotificationsPerPublish: 100, publishingEnabled: true, priority: 1,
    });
    const filter = opcua.constructEventFilter([...EVENT_FIELDS, "ConditionId"]);
    const item = await subscription.monitor(
      { nodeId: opts.notifier || "ns=0;i=2253", attributeId: opcua.AttributeIds.EventNotifier },
      { queueSize: 100, filter, discardOldest: true }, opcua.TimestampsToReturn.Both);
    item.on("changed", (fields) => {
      const event = {};
      [...EVENT_FIELDS, "ConditionId"].forEach((name, i) => { event[name] = plain(fields[i].value); });
      event.dataTypes = {};
      [...EVENT_FIELDS, "ConditionId"].forEach((name, i) => {
        event.dataTypes[name] = opcua.DataType[fields[i].dataType];
      });
      say({ event });
    });
    say({ subscribed: subscription.subscriptionId });
    if (opts.refresh) {
      const result = await session.call({
        objectId: "ns=0;i=2782", methodId: "ns=0;i=3875",
        inputArguments: [{ dataType: opcua.DataType.UInt32, value: subscription.subscriptionId }],
      });
      say({ refresh: result.statusCode.name });
    }
    await new Promise((resolve) => setTimeout(resolve, (opts.seconds || 5) * 1000));
  } finally {
    await session.close();
    await client.disconnect();
  }
}

async function walk(opts) {
  // the machine's tree, every variable read with its timestamps; the stack light elements'
  // SignalMode; the server's diagnostics summary and the ApplicationUri its endpoints name
  const { client, session } = await connect(opts);
  try {
    const ns = await namespaces(session);
    const machine = await machineNode(session, ns);
    const own = opcua.resolveNodeId(machine).namespace;
    const todo = [machine];
    const seen = new Set(todo);
    const variables = [];
    while (todo.length) {
      const node = todo.pop();
      const result = await session.browse({
        nodeId: node, browseDirection: opcua.BrowseDirection.Forward,
        referenceTypeId: "HierarchicalReferences", includeSubtypes: true, resultMask: 63,
      });
      for (const ref of result.references || []) {
        const id = ref.nodeId.toString();
        if (seen.has(id) || ref.nodeId.namespace !== own) continue;
        seen.add(id);
        todo.push(id);
        if (ref.nodeClass === opcua.NodeClass.Variable) variables.push([id, ref.browseName.name]);
      }
    }
    const values = await session.read(variables.map(([id]) => ({ nodeId: id })), 0);  // timestamps: both
    const noValue = [];
    const noTimestamp = [];
    values.forEach((dv, i) => {
      if (dv.value === null || dv.value.dataType === opcua.DataType.Null) noValue.push(variables[i][1]);
      if (!dv.sourceTimestamp || !dv.serverTimestamp) noTimestamp.push(variables[i][1]);
    });
    const signalModes = [];
    const stack = await session.translateBrowsePath(
      opcua.makeBrowsePath(machine, `/${ns.mt}:Monitoring/${ns.mt}:Stacklight`));
    const elements = await session.browse({
      nodeId: stack.targets[0].targetId, browseDirection: opcua.BrowseDirection.Forward,
      referenceTypeId: "HasOrderedComponent", includeSubtypes: true, resultMask: 63,
    });
    const ia = (await session.readNamespaceArray()).indexOf("http://opcfoundation.org/UA/IA/");
    for (const element of elements.references) {
      const mode = await session.translateBrowsePath(
        opcua.makeBrowsePath(element.nodeId, `/${ia}:SignalMode`));
      const target = mode.targets && mode.targets.length ? mode.targets[0].targetId : null;
      signalModes.push(target ? (await session.read({ nodeId: target })).value.value : null);
    }
    await new Promise((resolve) => setTimeout(resolve, 1500));  // the summary is counted once a second
    const summary = await session.read({ nodeId: "ns=0;i=2275" });
    const endpoints = await client.getEndpoints();
    say({
      variables: variables.length, noValue, noTimestamp, signalModes,
      diagnostics: plain(summary.value.value),
      applicationUris: [...new Set(endpoints.map((e) => e.server.applicationUri))],
    });
  } finally {
    await session.close();
    await client.disconnect();
  }
}

async function main() {
  const opts = JSON.parse(process.argv[2]);
  try {
    await { read, events, walk }[opts.action](opts);
  } catch (err) {
    say({ ok: false, error: String(err && err.message ? err.message : err) });
  }
  process.exit(0);
}

main();
