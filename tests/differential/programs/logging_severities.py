"""A node's logger as the tutorials use it: the five severities, the threshold, once and
skip_first, a child logger and a logger by name."""

import rclpy
from rclpy.logging import LoggingSeverity, get_logger
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('chatty')
    logger = node.get_logger()
    print('name:', logger.name, 'level:', logger.get_effective_level().name)
    logger.debug('debug is below the default threshold')
    logger.info('info')
    logger.warning('warning')
    logger.error('error')
    logger.fatal('fatal')
    logger.set_level(LoggingSeverity.DEBUG)
    logger.debug('debug once the level is DEBUG')
    print('level now:', logger.get_effective_level().name)
    for i in range(3):
        logger.info('only once, at %d' % i, once=True)
        logger.info('all but the first, at %d' % i, skip_first=True)
    child = logger.get_child('part')
    child.info('from the child')
    print('child name:', child.name)
    standalone = get_logger('standalone')
    standalone.info('from a logger by name')
    standalone.set_level(LoggingSeverity.ERROR)
    standalone.warning('hidden: below ERROR')
    standalone.error('shown: ERROR')
    logger.set_level(LoggingSeverity.WARN)
    logger.info('hidden: below WARN')
    logger.warning('shown: WARN')
    node.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
