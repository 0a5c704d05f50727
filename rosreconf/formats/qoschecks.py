"""Check that the QoS of a topic's publisher can serve its subscriptions (ROS 2).

Where a component declares a ``qos:`` for a topic, rmw's compatibility rule decides whether
a publisher and a subscription that a schema edge may join would exchange messages;
``checks.check`` runs this with the other semantic checks when some component declares one.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

from rosreconf.errors import Problem, Severity
from rosreconf.model import Component, InterfaceKind, InteroperabilitySchema
from rosreconf.model.qos import QosProfile, incompatibilities


def qos_problems(
    components: Sequence[Component], schemas: Sequence[InteroperabilitySchema]
) -> Iterator[Problem]:
    """Report topic edges whose publisher's QoS cannot serve the subscription's (ROS 2).

    Only where one side declares a QoS (the other then has the rmw default); ``checks.check``
    asks only when some component declares one. For each schema edge, every provider and
    consumer candidate pair sharing a topic is checked with ``model.qos.incompatibilities``
    (rmw's rule): an error when the schema's nominal configuration chooses the pair (it would
    run and exchange nothing), a warning otherwise (configurations choosing it are useless).
    """
    for schema in schemas:
        fit: dict[str, list[Component]] = {
            r.name: [
                c
                for c in components
                if c.abstraction == r.abstraction and c.may_serve_in(schema.name)
            ]
            for r in schema.graph.roles
        }
        nominal = dict(schema.nominal)
        for edge in schema.graph.edges:
            for provider in fit.get(edge.provider, []):
                for consumer in fit.get(edge.consumer, []):
                    chosen = (
                        nominal.get(edge.provider) == provider.name
                        and nominal.get(edge.consumer) == consumer.name
                    )
                    yield from _qos_pair(schema, edge.provider, provider, consumer, chosen)


def _qos_pair(
    schema: InteroperabilitySchema,
    role: str,
    provider: Component,
    consumer: Component,
    chosen: bool,
) -> Iterator[Problem]:
    """Check the topics ``consumer`` subscribes that ``provider`` publishes."""
    for i, req in enumerate(consumer.requires):
        for option in req.options:
            if option.kind is not InterfaceKind.TOPIC or option not in provider.provides:
                continue
            label = option.label
            if label not in provider.qos and label not in consumer.qos:
                continue
            offered = provider.qos.get(label, QosProfile())
            requested = consumer.qos.get(label, QosProfile())
            why = incompatibilities(offered, requested)
            if not why:
                continue
            where = consumer.at(f"qos.{label}" if label in consumer.qos else f"requires.{i}")
            scope = "the nominal" if chosen else "any"
            scope += f" configuration of {schema.name}" + ("" if chosen else " choosing both")
            yield Problem(
                where,
                f"topic '{label}': {provider.name} ({role}) offers QoS [{offered}] but "
                f"{consumer.name} requests [{requested}]: "
                f"{'; '.join(w.message for w in why)}; in {scope} no messages would flow",
                "make the publisher offer at least what the subscription requests "
                "(rmw's QoS compatibility rule), or relax the subscription's qos",
                "qos-incompatible",
                Severity.ERROR if chosen else Severity.WARNING,
            )
