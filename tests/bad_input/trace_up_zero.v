/* no direction at all */
trace up: 0,0,0
