"""Three details of rclpy's logger the lab's differs in: warn() still logs but says on stderr
that it is deprecated (a DeprecationWarning, shown as Python shows one), is_enabled_for(), and
a logging call's result (True when it logged, False when the threshold or once= held it back)."""

import rclpy
from rclpy.logging import LoggingSeverity
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('chatty')
    logger = node.get_logger()
    logger.warn('warn, the older name')
    try:
        print('enabled for DEBUG, INFO:', logger.is_enabled_for(LoggingSeverity.DEBUG),
              logger.is_enabled_for(LoggingSeverity.INFO))
    except AttributeError as exc:
        print('is_enabled_for:', type(exc).__name__)
    print('results:', logger.info('logged'), logger.debug('held back by the threshold'),
          logger.info('once', once=True), logger.info('once', once=True))
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
