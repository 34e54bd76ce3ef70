"""The Server object's ServerDiagnostics: enabled, and its summary counted from the guarded
connections and asyncua's own sessions and subscriptions.

Sessions that end without the client's CloseSession end by their timeout (asyncua keeps a
session whose connection dropped until then, for OPC UA's reconnect): they are the
SessionTimeoutCount. The server aborts no session, so SessionAbortCount stays 0, and it has
no views.
"""

from __future__ import annotations

from typing import Any

from asyncua import Server, ua

from opcua_server.channel import GuardCounts
from opcua_server.ids import nid

__all__ = ["Diagnostics"]

#: the first subscription id asyncua gives is this plus one
_FIRST_SUBSCRIPTION_ID = 77


def _u32(n: int) -> ua.UInt32:
    return ua.UInt32(max(0, int(n)))


class Diagnostics:
    def __init__(self, server: Server, counts: GuardCounts) -> None:
        self.server, self.counts = server, counts
        self._last: ua.ServerDiagnosticsSummaryDataType | None = None

    async def enable(self) -> None:
        aspace = self.server.iserver.aspace
        await aspace.write_attribute_value(nid(ua.ObjectIds.Server_ServerDiagnostics_EnabledFlag),
                                           ua.AttributeIds.Value,
                                           ua.DataValue(ua.Variant(True, ua.VariantType.Boolean)))
        await self.update()

    def summary(self) -> ua.ServerDiagnosticsSummaryDataType:
        iserver: Any = self.server.iserver
        c = self.counts
        current = len(iserver._external_sessions)
        service = iserver.subscription_service
        subscriptions = service.subscriptions
        intervals = {sub.data.RevisedPublishingInterval for sub in subscriptions.values()}
        s = ua.ServerDiagnosticsSummaryDataType()
        s.ServerViewCount = _u32(0)
        s.CurrentSessionCount = _u32(current)
        s.CumulatedSessionCount = _u32(c.created_sessions)
        s.SecurityRejectedSessionCount = _u32(c.security_rejected)
        s.RejectedSessionCount = _u32(c.rejected_sessions)
        s.SessionTimeoutCount = _u32(c.created_sessions - c.closed_sessions - current)
        s.SessionAbortCount = _u32(0)
        s.CurrentSubscriptionCount = _u32(len(subscriptions))
        s.CumulatedSubscriptionCount = _u32(service._sub_id_counter - _FIRST_SUBSCRIPTION_ID)
        s.PublishingIntervalCount = _u32(len(intervals))
        s.SecurityRejectedRequestsCount = _u32(c.security_rejected)
        s.RejectedRequestsCount = _u32(c.rejected_requests)
        return s

    async def update(self) -> None:
        """Write the summary when it changed."""
        s = self.summary()
        if s == self._last:
            return
        self._last = s
        await self.server.iserver.aspace.write_attribute_value(
            nid(ua.ObjectIds.Server_ServerDiagnostics_ServerDiagnosticsSummary), ua.AttributeIds.Value,
            ua.DataValue(ua.Variant(s, ua.VariantType.ExtensionObject)))
